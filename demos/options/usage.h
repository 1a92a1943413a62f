#pragma once
// What both programs (particle-lab, particle-demo) do with a bad command line:
// one line on stderr and exit code 2.
#include <stdexcept>
#include <string>

namespace options {

// Exit code of a bad option value or combination, a missing or malformed scene file.
constexpr int kBadUsageExit = 2;
// Exit code of an output that could not be written (a full disk, /dev/full, an
// I/O error), in both programs.
constexpr int kWriteFailedExit = 4;

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

// Flushes standard output (std::cout and stdout): empty when all that was
// written reached it, else why not ("cannot write the standard output: No
// space left on device"): what a program's result or --help on a full disk,
// /dev/full or a closed pipe gets instead of exit 0.
std::string flushStandardOutput();

}  // namespace options
