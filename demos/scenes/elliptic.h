#pragma once
// The elliptic integrals of the first kind that the pendulum's closed form
// needs: F(φ, k) = ∫₀^φ dθ / √(1 − k² sin²θ) and K(k) = F(π/2, k), modulus k.
// The C++17 special functions where the standard library has them
// (libstdc++), Boost.Math's where it has not (libc++, the WebAssembly build).
#include <cmath>
#if !defined(__STDCPP_MATH_SPEC_FUNCS__)
#include <boost/math/special_functions/ellint_1.hpp>
#endif

namespace scenes {

inline double ellipticK(double k) {
#if defined(__STDCPP_MATH_SPEC_FUNCS__)
  return std::comp_ellint_1(k);
#else
  return boost::math::ellint_1(k);
#endif
}

inline double ellipticF(double k, double phi) {
#if defined(__STDCPP_MATH_SPEC_FUNCS__)
  return std::ellint_1(k, phi);
#else
  return boost::math::ellint_1(k, phi);
#endif
}

}  // namespace scenes
