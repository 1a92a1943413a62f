#include "options/usage.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>

#include "output/printable.h"

namespace options {

std::string versionLine(const char* program) { return std::string(program) + " " + PARTICLES_VERSION; }

void printErrorLine(const char* program, const std::string& message) {
  std::fprintf(stderr, "%s: %s\n", program, output::printable(message).c_str());
}

std::string flushStandardOutput() {
  errno = 0;
  std::cout.flush();
  if (std::cout && std::fflush(stdout) == 0) return {};
  return std::string("cannot write the standard output: ") + (errno ? std::strerror(errno) : "the write failed");
}

}  // namespace options
