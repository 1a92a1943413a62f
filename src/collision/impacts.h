#pragma once
// The impacts stage of the contact pass: bounces at their exact times.
//
// A particle that moves alone — in no constraint, or held only by constraints
// whose other particles are pinned (a bead on a wire, a bob on a rod to a
// pin) — follows its path through the step (contact_path.h) until its first
// impact on a collider or another disc that moves alone; there its velocity jumps (restitution along the
// normal, Coulomb friction along the surface, a pair's equal and opposite
// impulses j = −(1 + e) u_n / (w_i + w_j)) and the rest of its path, and so
// the step's end, is displaced by Δv (dt − τ); a held particle moves only
// along its constraints (contact_track.h, Track::mobility). Impacts are taken in the order
// of their times, each on the paths the particles really follow then (an
// event queue over the discs; a point meets only colliders, one impact after
// another), so an elastic bounce in uniform gravity is exact, a Newton's
// cradle passes its momentum down the row, and a point in a wedge follows the
// unfolded billiard.
//
// Only bounces are impacts: a contact whose bounce would not clear the
// surface by the step's end (e = 0, or a slow approach) rests, and is left
// where the path meets it for the solver (contact_solver.h), which holds
// resting contacts, friction and everything constrained together. The path
// from a particle's last impact is its reference for that solve (Reference).
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "contact_types.h"
#include "particles/collider.h"
#include "particles/collision.h"

namespace particles {

// A particle held by constraints whose other particles are pinned, and the
// projector onto the velocities they leave it (contact_track.h).
struct Anchored {
  int particle;
  Eigen::Matrix2d mobility;
};

class Impacts {
 public:
  Impacts();
  ~Impacts();
  Impacts(Impacts&&) noexcept;
  Impacts& operator=(Impacts&&) noexcept;

  // Bounces of the points in `points` against the colliders, and of the discs
  // in `discs` against the colliders and each other (pairs: indices into
  // discs, each pair once), over the step from `start` to (x, v). Every
  // particle listed moves alone; `anchored` (sorted by particle) gives those
  // held by constraints. Updates (x, v) and the references of the particles
  // that bounced. Returns the impacts and the particles that ran out of
  // ContactSettings::maxImpacts.
  ContactCount resolve(const std::vector<Collider>& colliders, const std::vector<int>& points,
                       const std::vector<int>& discs, const std::vector<std::pair<int, int>>& pairs,
                       const std::vector<Anchored>& anchored, const StepStart& start,
                       const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                       const ContactSettings& settings, Eigen::VectorXd& x, Eigen::VectorXd& v, References& refs);

 private:
  ContactCount resolvePoints(const std::vector<Collider>& colliders, const std::vector<int>& points,
                             const std::vector<Anchored>& anchored, const StepStart& start, const Eigen::VectorXd& inverseMass,
                             const Eigen::VectorXd& radius, const ContactSettings& settings, Eigen::VectorXd& x,
                             Eigen::VectorXd& v, References& refs);
  ContactCount resolveDiscs(const std::vector<Collider>& colliders, const std::vector<int>& discs,
                            const std::vector<std::pair<int, int>>& pairs, const std::vector<Anchored>& anchored,
                            const StepStart& start,
                            const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                            const ContactSettings& settings, Eigen::VectorXd& x, Eigen::VectorXd& v,
                            References& refs);

  struct Scratch;  // event queue and tracks, kept between steps to avoid allocation
  std::unique_ptr<Scratch> scratch_;
};

}  // namespace particles
