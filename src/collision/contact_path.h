#pragma once
// What every contact kind shares: the model of a particle's motion within a
// step and the response at a contact on it.
#include <algorithm>
#include <cmath>
#include <optional>

#include <Eigen/Core>

#include "contact_types.h"
#include "particles/collider.h"
#include "particles/collision.h"

namespace particles::contact {

// The path of constant acceleration through the step's two ends,
//   a = (v₁ − v₀)/dt,  u₀ = (x₁ − x₀)/dt − ½ a dt,  q(τ) = x₀ + u₀ τ + ½ a τ²,
// so q(dt) = x₁. Under RK4 in uniform gravity u₀ = v₀ and q is the exact
// trajectory; under symplectic Euler u₀ = v₀ + ½ a dt, the scheme's mean
// velocity, which is what keeps its bounce from draining energy (its
// velocity leads its position by half a step).
struct Path {
  Eigen::Vector2d x0, u0, a;
  double t0 = 0.0;  // time the path starts at, within the step

  static Path through(const Eigen::Vector2d& x0, const Eigen::Vector2d& v0, const Eigen::Vector2d& x1,
                      const Eigen::Vector2d& v1, double dt) {
    const Eigen::Vector2d a = (v1 - v0) / dt;
    return {x0, (x1 - x0) / dt - 0.5 * a * dt, a, 0.0};
  }
  // Particle i's path in a step, through its start and its current end.
  static Path of(const StepStart& start, int i, const Eigen::VectorXd& x, const Eigen::VectorXd& v) {
    return through(start.x.segment<2>(2 * i), start.v.segment<2>(2 * i), x.segment<2>(2 * i), v.segment<2>(2 * i),
                   start.dt);
  }
  Eigen::Vector2d position(double t) const {
    const double s = t - t0;
    return x0 + u0 * s + 0.5 * a * s * s;
  }
  Eigen::Vector2d velocity(double t) const { return u0 + a * (t - t0); }
};

// Normal velocity change at a contact with approach speed u_n (< 0 when
// approaching), normal acceleration a_n and time left R. The surface leaves
// with w = −e u_n; it is a bounce if the flight w R + ½ a_n R² keeps it clear
// to the end of the step, otherwise the contact rests (and the caller holds it
// on the surface with the impulse that cancels its normal velocity at the end).
struct NormalChange {
  bool resting;
  double dv;  // bounce: velocity change along the normal
};
inline NormalChange normalChange(double un, double an, double remaining, double restitution) {
  const double w = un < 0.0 ? -restitution * un : un;
  if (w > 0.0 && w * remaining + 0.5 * an * remaining * remaining >= 0.0) return {false, w - un};
  return {true, 0.0};
}

// Coulomb friction: the tangential velocity change that stops the sliding
// velocity vt, limited to μ times the normal velocity change |dvn|.
inline Eigen::Vector2d coulomb(const Eigen::Vector2d& vt, double dvn, double friction) {
  const double speed = vt.norm(), limit = friction * std::abs(dvn);
  if (speed <= limit) return -vt;
  return -vt * (limit / speed);
}

// Smallest s ∈ [0, 1] at which the path a + s d enters the circle |x − c| = R, if any.
inline std::optional<double> enterCircle(const Eigen::Vector2d& a, const Eigen::Vector2d& d, const Eigen::Vector2d& c,
                                         double R) {
  const Eigen::Vector2d m = a - c;
  const double A = d.squaredNorm(), B = m.dot(d), C = m.squaredNorm() - R * R;
  if (A == 0.0 || B >= 0.0) return std::nullopt;  // not moving towards the centre
  const double disc = B * B - A * C;
  if (disc < 0.0) return std::nullopt;
  const double s = (-B - std::sqrt(disc)) / A;
  // An entry at the very end of the path, within the round-off of s, enters
  // (a disc that reaches another exactly at a step's end strikes it then).
  if (s < 0.0 || s > 1.0 + 1e-12) return std::nullopt;
  return std::min(s, 1.0);
}

}  // namespace particles::contact
