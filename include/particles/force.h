#pragma once
// The Force interface: every force type adds its contribution to the 2n force
// accumulator Q and, where it has one, reports its potential energy.
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <utility>
#include <vector>

#include "particles/phase.h"

namespace particles {

using Triplets = std::vector<Eigen::Triplet<double>>;

// Links between two particles that have broken (torn springs), each stored
// as (min, max) and sorted, so that a force can ask whether one of its own
// links is among them in O(log n).
class LinkSet {
 public:
  explicit LinkSet(std::vector<std::array<int, 2>> links) : links_(std::move(links)) {
    for (auto& link : links_)
      if (link[0] > link[1]) std::swap(link[0], link[1]);
    std::sort(links_.begin(), links_.end());
  }
  bool contains(int i, int j) const {
    return std::binary_search(links_.begin(), links_.end(), std::array<int, 2>{std::min(i, j), std::max(i, j)});
  }
  bool empty() const { return links_.empty(); }
  const std::vector<std::array<int, 2>>& links() const { return links_; }

 private:
  std::vector<std::array<int, 2>> links_;
};

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

  // A force that changes with time (wind gusts) says so and is told the
  // system's clock once per step, at the step's start, by ParticleSystem::step
  // (and when the system is restored or the force added): it holds its value
  // over the step, so every stage of an integrator sees the same force law.
  virtual bool timeDependent() const { return false; }
  virtual void setTime(double /*time*/) {}

  // Drops what of this force hangs on a link that broke (ParticleSystem::
  // breakLinks): a spring on it is torn, an angle spring with it as an arm
  // goes with it, the wind no longer pushes on it. True when something changed.
  virtual bool dropLinks(const LinkSet& /*broken*/) { return false; }
  // Links that break with `broken` (ParticleSystem::breakLinks asks before
  // anything drops): a face with a torn side tears out, and every link
  // across it (a cloth cell's diagonals) goes with it. Appended to more.
  virtual void linksBreakingWith(const LinkSet& /*broken*/, std::vector<std::array<int, 2>>& /*more*/) const {}

  // Lines and circles that show this force (springs as lines); none by default.
  virtual void sketch(const Phase&, Sketch&) const {}
};

}  // namespace particles
