#pragma once
// Mathematical constants shared by the engine, the scenes, the demo and the
// tests: one definition each (C++17 has no std::numbers, and M_PI is POSIX,
// not standard C++).

namespace particles {

// π to the precision of a double.
inline constexpr double kPi = 3.14159265358979323846;

}  // namespace particles
