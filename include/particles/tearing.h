#pragma once
// Tearing: springs that break where they are stretched too far.
//
// A spring between x_i and x_j of rest length r tears when its strain
//   ε = |x_j − x_i| / r − 1
// exceeds the limit ε_max set for the scene. The test is made once per step,
// at its end (the tear phase of ParticleSystem::step, after the contacts),
// on every intact spring at once from the same positions, and the links of
// those over the limit break together (ParticleSystem::breakLinks: the
// springs tear, angle springs with a torn arm go with them, the wind no
// longer pushes on a torn side, collision edges on it are removed, and a
// face of a face-area force with a torn side tears out with its diagonals,
// so that a pulled cloth rips along a line of faces). So a
// spring is never torn inside a step: every stage of an integrator (RK4's
// four evaluations, xpbd's substeps, implicit Euler's Newton passes) sees the
// same springs, the result does not depend on the order of the springs, and
// a run repeats exactly. A torn spring stays torn (restore() leaves it so;
// only ParticleSystem::setSpringEnabled mends one).
#include <array>
#include <cstdint>
#include <vector>

namespace particles {

class ParticleSystem;
class SpringForce;

struct TearSettings {
  double strain = 0.0;  // ε_max ≥ 0: springs stretched beyond it tear; 0: nothing tears
  bool on() const { return strain > 0.0; }
  void validate() const;  // throws std::invalid_argument naming the value
};

class Tearing {
 public:
  TearSettings settings;

  // The tear phase: breaks the link of every intact spring whose strain
  // exceeds settings.strain at the system's present positions; returns how
  // many links broke. Nothing when tearing is off.
  int tear(ParticleSystem& system);
  int tornLastStep() const { return tornLastStep_; }

 private:
  // The intact springs, gathered again when the system's structure changes.
  void gather(const ParticleSystem& system);
  std::vector<const SpringForce*> springs_;
  std::uint64_t gatheredStamp_ = 0;
  std::vector<std::array<int, 2>> breaking_;
  int tornLastStep_ = 0;
};

}  // namespace particles
