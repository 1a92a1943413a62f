#include "options/usage.h"

#include <cstdio>

#include "output/printable.h"

namespace options {

std::string versionLine(const char* program) { return std::string(program) + " " + PARTICLES_VERSION; }

void printErrorLine(const char* program, const std::string& message) {
  std::fprintf(stderr, "%s: %s\n", program, output::printable(message).c_str());
}

}  // namespace options
