#pragma once
// The Constraint interface: a scalar constraint C(q) = 0 on a few particles,
// exposing C, Ċ and the sparse blocks of its rows of J = ∂C/∂q and J̇ —
// one 2-vector block per particle involved.
#include <array>
#include <memory>
#include <vector>

#include "particles/phase.h"

namespace particles {

// Value of one constraint and its J, J̇ blocks for N particles: the output of
// the pure kernels in constraints/*.h, which need no ParticleSystem.
template <int N>
struct ConstraintKernel {
  double C = 0.0;
  double Cdot = 0.0;
  std::array<Eigen::Vector2d, N> J;
  std::array<Eigen::Vector2d, N> Jdot;
};

// Where a constraint writes its row: J and Jdot point at particles().size()
// blocks owned by the solver.
struct ConstraintRow {
  double C = 0.0;
  double Cdot = 0.0;
  Eigen::Vector2d* J = nullptr;
  Eigen::Vector2d* Jdot = nullptr;
};

class Constraint {
 public:
  explicit Constraint(std::vector<int> particles) : particles_(std::move(particles)) {}
  virtual ~Constraint() = default;

  virtual const char* type() const = 0;
  const std::vector<int>& particles() const { return particles_; }

  // Fills C, Ċ and the J, J̇ blocks (in the order of particles()).
  virtual void evaluate(const Phase& s, ConstraintRow& row) const = 0;

  // Geometric violation in world length units (|C| of the root form), so the
  // squared and root rods report comparable errors.
  virtual double violation(const Phase& s) const = 0;
  // Length that makes violation() relative (rod length, wire radius); 0 if none.
  virtual double lengthScale() const = 0;

  virtual void sketch(const Phase& s, Sketch& out) const = 0;

 private:
  std::vector<int> particles_;
};

using ConstraintList = std::vector<std::unique_ptr<Constraint>>;

}  // namespace particles
