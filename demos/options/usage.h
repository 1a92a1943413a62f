#pragma once
// What both programs (particle-lab, particle-demo) do with a bad command line:
// one line on stderr and exit code 2.
#include <stdexcept>
#include <string>

namespace options {

// Exit code of a bad option value or combination, a missing or malformed scene file.
constexpr int kBadUsageExit = 2;

// A bad option value or combination found after parsing.
class UsageError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// "PROGRAM VERSION" (the CMake project's version): what --version prints.
std::string versionLine(const char* program);

// Writes "PROGRAM: MESSAGE" as one line on stderr; control characters in the
// message (a file name's newline, an escape) are escaped (printable.h).
void printErrorLine(const char* program, const std::string& message);

}  // namespace options
