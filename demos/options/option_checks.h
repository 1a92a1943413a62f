#pragma once
// CLI11 validators shared by particle-lab's subcommands and particle-demo.
//
// CLI11 reads integers with strtoll(…, 0), so "010" is octal 8, "0x10" is 16
// and a value beyond the type is clamped; these validators run on the text
// first and accept only a plain decimal integer inside a range.
#include <string>

#include <CLI/CLI.hpp>

namespace options {

// "[-]digits" with a value in [lo, hi]; anything else is rejected with a
// message naming the accepted range.
CLI::Validator decimalInteger(long long lo, long long hi);

// An existing regular file: CLI::ExistingFile also passes devices and FIFOs
// (/dev/zero would be read forever, a FIFO waited on).
CLI::Validator regularFile();

// A tolerance the adaptive integrators accept (IntegratorSettings::validate):
// "--tolerance: integrator tolerance must be > 0, got 0".
CLI::Validator integratorTolerance();

// A number > 0 and finite, or one in [lo, hi], in the engine's words (checks
// in particles/check.h): "--dt: value must be > 0, got nan". Text that is no
// number is left to the conversion, which names it.
CLI::Validator positiveNumber();
CLI::Validator numberInRange(double lo, double hi);

// A file to write: an empty name ("") is refused instead of writing nothing.
CLI::Validator outputPath();

// An integrator of the table, by name: "unknown integrator 'rk5' (valid: …)".
CLI::Validator integratorName();

}  // namespace options
