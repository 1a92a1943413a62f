#pragma once
// Wind: air moving at a velocity w(t) that drags on the edges of a surface
// (a cloth's sides, a strand's links). In 2D a surface is a curve, so the
// face of the 3D drag law becomes an edge: the air pushes an edge along its
// normal n with the pressure of the normal component of the air's velocity
// relative to the edge,
//   u = w(t) − ½ (v_i + v_j),   u_n = u·n,   F = c |d| |u_n| u_n n,
// with d = x_j − x_i and c = ½ ρ C_d per unit depth (force per length per
// speed²), half of F on each end. A sheet across the wind takes the full
// pressure, an edge along it none; the edge's own motion counts, so the wind
// also damps an edge moving through still air. F does not change sign with n.
//
// Gusts: the speed swings about its mean U as U (1 + A γ(t)) with
//   γ(t) = Σ_k a_k sin(2π t/T_k + φ_k) / Σ_k a_k  ∈ [−1, 1],
//   T_k = T, T/2.13, T/4.37 (incommensurate, so the pattern never repeats
//   exactly), a_k = 1, 0.6, 0.35, and phases φ_k drawn from the seed;
// a pure function of time and seed, so a run repeats exactly. The air
// velocity is sampled once per step, at its start (Force::setTime), and held
// over the step, so every stage of an integrator sees the same force law.
#include <array>
#include <vector>

#include <Eigen/Core>

#include "particles/force.h"

namespace particles {

struct WindSettings {
  double speed = 0.0;       // U, mean air speed, world units / s
  double direction = 0.0;   // φ, radians counter-clockwise from +x: the way the air moves
  double drag = 0.0;        // c, force / (length · speed²): ½ ρ C_d per unit depth
  double gust = 0.0;        // A in [0, 1]: the speed swings between (1 − A) U and (1 + A) U
  double gustPeriod = 2.0;  // T, s: the slowest of the gusts' three periods
  int seed = 1;             // ≥ 0: chooses the gusts' phases
  void validate() const;    // throws std::invalid_argument naming the field
};

// γ(t) above, in [−1, 1].
double gustShape(double time, double period, int seed);
// w(t) = U (1 + A γ(t)) (cos φ, sin φ).
Eigen::Vector2d airVelocity(const WindSettings& wind, double time);

// The force of the air on one edge d = x_j − x_i, with u the air's velocity
// relative to the edge: F = c |d| |u_n| u_n n (each end takes F/2). With
// a = R d (d turned by +90°, |a| = |d|) and p = u·a, F = c |p| p a / |a|².
Eigen::Vector2d windEdgeForce(const Eigen::Vector2d& d, const Eigen::Vector2d& u, double drag);
// ∂F/∂d and ∂F/∂u of windEdgeForce:
//   ∂F/∂u = 2c |p| a aᵀ/|a|²,
//   ∂F/∂a = c [2|p| a uᵀ + |p| p I − 2|p| p a aᵀ/|a|²] / |a|²,   ∂F/∂d = ∂F/∂a R.
// Both 0 for an edge of length 0.
void windEdgeJacobian(const Eigen::Vector2d& d, const Eigen::Vector2d& u, double drag, Eigen::Matrix2d& dFdd,
                      Eigen::Matrix2d& dFdu);

class WindForce : public Force {
 public:
  // Edges as particle index pairs; the settings are validated.
  WindForce(std::vector<std::array<int, 2>> edges, const WindSettings& settings);

  const char* type() const override { return "wind"; }
  void apply(const Phase& s, Eigen::VectorXd& f) const override;
  std::vector<int> particles() const override;
  bool hasJacobians() const override { return true; }
  // Exact: ∂f/∂x through each edge's length and normal, ∂f/∂v through u.
  void addJacobians(const Phase& s, Triplets& dfdx, Triplets& dfdv) const override;
  // ∂f/∂v alone, −½ c |d| |u_n| n nᵀ on the four blocks of each edge: symmetric
  // negative semi-definite; the position part (the edge turning in the wind)
  // is not symmetric and is dropped.
  void addDefiniteJacobians(const Phase& s, Triplets& dfdx, Triplets& dfdv) const override;
  bool timeDependent() const override { return true; }
  void setTime(double time) override;
  // The edges on a broken link are dropped: the air no longer pushes on a torn side.
  bool dropLinks(const LinkSet& broken) override;

  const std::vector<std::array<int, 2>>& edges() const { return edges_; }
  const WindSettings& settings() const { return settings_; }
  // New settings (validated), sampled at the time last set.
  void setSettings(const WindSettings& settings);
  // The air velocity w of the present step.
  const Eigen::Vector2d& air() const { return air_; }

 private:
  Eigen::Vector2d relativeAir(const Phase& s, int i, int j) const;
  std::vector<std::array<int, 2>> edges_;
  WindSettings settings_;
  double time_ = 0.0;
  Eigen::Vector2d air_ = Eigen::Vector2d::Zero();
};

}  // namespace particles
