#pragma once
// The Force interface: every force type adds its contribution to the 2n force
// accumulator Q and, where it has one, reports its potential energy.
#include <Eigen/SparseCore>
#include <vector>

#include "particles/phase.h"

namespace particles {

using Triplets = std::vector<Eigen::Triplet<double>>;

class Force {
 public:
  virtual ~Force() = default;

  // Name used in scene files and on screen ("spring", "gravity", ...).
  virtual const char* type() const = 0;

  // Adds this force's contribution at phase s into f (size 2n).
  virtual void apply(const Phase& s, Eigen::VectorXd& f) const = 0;

  // Potential energy E with f = −∂E/∂x, for forces that have one.
  virtual bool hasPotential() const { return false; }
  virtual double potential(const Phase&) const { return 0.0; }

  // Particles this force acts on (empty: a field acting on every particle).
  virtual std::vector<int> particles() const { return {}; }

  // Force Jacobians ∂f/∂x and ∂f/∂v as triplets in 2n × 2n coordinates, for
  // implicit integrators. A force that cannot provide them says so, and an
  // implicit integrator refuses the system at setup.
  virtual bool hasJacobians() const { return false; }
  virtual void addJacobians(const Phase&, Triplets& dfdx, Triplets& dfdv) const;

  // The same Jacobians made symmetric negative semi-definite, so that an
  // implicit step's M − h ∂f/∂v − h² ∂f/∂x is symmetric positive definite:
  // springs under compression drop their transverse term (Choi & Ko 2002),
  // non-symmetric damping parts of ∂f/∂x are dropped, angle springs keep the
  // Gauss–Newton term. Forces whose exact Jacobians already are keep the default.
  virtual void addDefiniteJacobians(const Phase& s, Triplets& dfdx, Triplets& dfdv) const {
    addJacobians(s, dfdx, dfdv);
  }

  // Lines and circles that show this force (springs as lines); none by default.
  virtual void sketch(const Phase&, Sketch&) const {}
};

}  // namespace particles
