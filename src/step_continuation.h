#pragma once
// What a scheme may carry from one step to the next (velocity Verlet's last
// acceleration, dopri5's internal solution and FSAL stage): valid only while
// the system is exactly as the last step left it. A change of state (a
// contact, a drag, a restore), of structure (a spring torn, a force added)
// or of a force that follows the clock (wind gusts, sampled at each step's
// start) makes the scheme start afresh from the system's state.
#include <cstdint>

#include <Eigen/Core>

namespace particles {

class ParticleSystem;

class StepContinuation {
 public:
  // True when the system holds exactly the state, structure and forces kept.
  bool matches(const ParticleSystem& system) const;
  // Keeps the system's state and structure as the step leaves them.
  void keep(const ParticleSystem& system);

 private:
  Eigen::VectorXd x_, v_;
  std::uint64_t stamp_ = 0;
  bool kept_ = false;
};

}  // namespace particles
