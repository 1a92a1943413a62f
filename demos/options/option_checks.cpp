#include "options/option_checks.h"

#include <charconv>

#include <sys/stat.h>

#include "decimal_number.h"
#include "particles/check.h"
#include "particles/integrator.h"

namespace options {

CLI::Validator decimalInteger(long long lo, long long hi) {
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        const char* first = text.data();
        const char* last = first + text.size();
        long long value = 0;
        const auto result = std::from_chars(first, last, value);  // decimal only, no '+', no prefix
        const bool digitsOnly = result.ptr == last && result.ec == std::errc() &&
                                !(text.size() > 1 && text[0] == '0') && text.rfind("-0", 0) != 0;
        if (result.ec == std::errc::result_out_of_range || (digitsOnly && (value < lo || value > hi)))
          return "expected a decimal integer in " + range + ", got " + text;
        if (!digitsOnly) return "expected a decimal integer in " + range + " (no leading zeros or 0x), got " + text;
        return {};
      },
      "INT in " + range);
}

CLI::Validator regularFile() {
  return CLI::Validator(
      [](std::string& path) -> std::string {
        struct stat info {};
        if (::stat(path.c_str(), &info) != 0) return "File does not exist: " + path;
        if (!S_ISREG(info.st_mode)) return "not a regular file: " + path;
        return {};
      },
      "FILE");
}

CLI::Validator outputPath() {
  return CLI::Validator(
      [](std::string& path) -> std::string { return path.empty() ? "expected a file name, got \"\"" : ""; },
      "FILE");
}

CLI::Validator integratorTolerance() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        particles::IntegratorSettings settings;
        try {
          settings.dopri5.tolerance = scenes::readDecimalNumber(text);
          settings.validate();
        } catch (const std::invalid_argument& e) {
          return e.what();
        }
        return {};
      },
      "TOLERANCE");
}

namespace {

// A validator that reads the text as a decimal number (decimal_number.h) and
// runs `check` on it, returning the message of the std::invalid_argument
// either throws.
template <class Check>
CLI::Validator numberCheck(Check check, std::string description) {
  return CLI::Validator(
      [check](std::string& text) -> std::string {
        try {
          check(scenes::readDecimalNumber(text));
        } catch (const std::invalid_argument& e) {
          return e.what();
        }
        return {};
      },
      std::move(description));
}

}  // namespace

CLI::Validator positiveNumber() {
  return numberCheck([](double value) { particles::requirePositive("value", value); }, "NUMBER > 0");
}

CLI::Validator numberInRange(double lo, double hi) {
  return numberCheck([lo, hi](double value) { particles::requireInRange("value", value, lo, hi); },
                     "NUMBER in [" + particles::formatValue(lo) + ", " + particles::formatValue(hi) + "]");
}

CLI::Validator integratorName() {
  return CLI::Validator(
      [](std::string& name) -> std::string {
        try {
          particles::requireIntegrator(name);
        } catch (const std::invalid_argument& e) {
          return e.what();
        }
        return {};
      },
      "INTEGRATOR");
}

}  // namespace options
