#pragma once
// Parameter validation shared by every object that takes user input.
// Each check throws std::invalid_argument naming the parameter and its value,
// so a bad scene file or command line produces one clear line, never UB.
#include <cmath>
#include <stdexcept>
#include <string>

namespace particles {

// A value in an error message: 6 significant digits, as printf's %.6g
// ("got 1e+308", "got nan").
std::string formatValue(double value);

inline void requireFinite(const char* name, double value) {
  if (!std::isfinite(value))
    throw std::invalid_argument(std::string(name) + " must be finite, got " + formatValue(value));
}

// An infinite value is named as such: "must be finite and > 0, got inf".
inline void requirePositive(const char* name, double value) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw std::invalid_argument(std::string(name) + (std::isinf(value) ? " must be finite and > 0, got " : " must be > 0, got ") +
                                formatValue(value));
}

inline void requireNonNegative(const char* name, double value) {
  if (!(value >= 0.0) || !std::isfinite(value))
    throw std::invalid_argument(std::string(name) +
                                (std::isinf(value) ? " must be finite and >= 0, got " : " must be >= 0, got ") +
                                formatValue(value));
}

inline void requireInRange(const char* name, double value, double lo, double hi) {
  if (!(value >= lo && value <= hi))
    throw std::invalid_argument(std::string(name) + " must be in [" + formatValue(lo) + ", " +
                                formatValue(hi) + "], got " + formatValue(value));
}

inline void requireIndex(const char* name, int index, int count) {
  if (index < 0 || index >= count)
    throw std::invalid_argument(std::string(name) + " names particle " + std::to_string(index) +
                                ", but the system has " + std::to_string(count) + " particles");
}

}  // namespace particles
