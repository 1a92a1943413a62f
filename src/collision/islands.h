#pragma once
// Islands and sleep: model only what the scene requires.
//
// Particles joined by constraints, by forces between particles (springs,
// angle springs, the wind's edges) or by a contact of the last step, through
// particles that move (a pin joins nothing), form islands. Each particle
// keeps the time it has moved slower than ContactSettings::sleepSpeed; an
// island whose particles have all done so for sleepTime, that touches
// something (a collider or another island: a pile, a rope at rest on a peg)
// and that no time-dependent force or mouse joint acts on falls asleep. A
// sleeping particle is held where it fell asleep, at rest: the contact pass
// sees it as pinned, and a step with nothing awake integrates and collides
// nothing. An island wakes when an awake particle touches one of its
// particles (the contact is resolved against it as against a pinned particle
// in that step, and it moves from the next), and every island wakes when the
// system is edited (particles, forces, constraints, pins, colliders or the
// state set from outside). A scene that keeps moving never sleeps, so sleep
// never changes a moving scene's trajectory.
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "contact.h"
#include "particles/collision.h"
#include "particles/constraint.h"
#include "particles/force.h"

namespace particles {

// What the sleep phase reads of a particle system after a step.
struct SleepScene {
  const std::vector<std::unique_ptr<Force>>& forces;
  const ConstraintList& constraints;
  const std::vector<Contact>& contacts;  // the last contact pass's
  const Eigen::VectorXd& inverseMass;    // the system's own (a pin has 0)
  std::uint64_t structure;               // ParticleSystem::structureStamp()
};

class Islands {
 public:
  // The inverse masses the step sees: a sleeping particle's is 0. Returns
  // `w` itself when nothing sleeps.
  const Eigen::VectorXd& inverseMasses(const Eigen::VectorXd& w) const;
  // Puts every sleeping particle back where it fell asleep, at rest.
  void hold(Eigen::VectorXd& x, Eigen::VectorXd& v) const;
  // After a step of dt: wakes the islands an awake particle touched, adds dt
  // to the rest time of each slow particle, and puts to sleep the islands
  // that rested long enough.
  void update(const SleepScene& scene, const ContactSettings& settings, const Eigen::VectorXd& x,
              const Eigen::VectorXd& v, double dt);
  void wakeAll();

  int sleeping() const { return sleeping_; }
  bool anyAsleep() const { return sleeping_ > 0; }
  bool allAsleep() const { return sleeping_ > 0 && sleeping_ == static_cast<int>(asleep_.size()); }
  bool asleep(int i) const { return i < static_cast<int>(asleep_.size()) && asleep_[i]; }

 private:
  void buildLinks(const SleepScene& scene, int n);
  void findIslands(const SleepScene& scene, int n);
  void wake(int particle);

  std::vector<char> asleep_;
  std::vector<int> group_;            // a sleeping particle's island, as its first particle; −1 awake
  std::vector<double> rested_;        // per particle: time moving slower than sleepSpeed
  Eigen::VectorXd held_;              // 2n: where the sleeping particles fell asleep
  mutable Eigen::VectorXd effective_;  // the inverse masses with the sleeping ones 0 (inverseMasses)
  std::uint64_t structure_ = 0;
  std::vector<std::pair<int, int>> links_;  // constraint and force links, rebuilt when the structure changes
  std::vector<char> keptAwake_;             // per particle: a time-dependent force or a mouse joint acts on it
  std::vector<int> parent_, island_, members_, memberStart_;
  double sinceIslands_ = 0.0;  // time since the islands were last found
  int sleeping_ = 0;
};

}  // namespace particles
