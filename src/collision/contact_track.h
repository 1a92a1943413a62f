#pragma once
// One particle's motion through the impacts stage of a step (impacts.h), and
// its impacts against colliders found and applied one at a time.
#include <algorithm>
#include <limits>
#include <optional>
#include <vector>

#include "contact_path.h"

namespace particles::contact {

// The particle's path since its last event (path.t0, at path.x0: the step's
// start or its last impact) and the step's end it leads to.
// mobility: the velocities the particle's constraints leave it, as the
// projector P onto them (the identity for a particle in no constraint; for a
// bead on a wire or a bob on a rod to a pin, the tangent of its circle): an
// impulse along n changes its velocity along P n only, as the constraint's
// own impulse takes the rest.
struct Track {
  Path path;
  Eigen::Vector2d x1, v1;  // end of the step
  int impacts = 0;         // events so far in this step
  Eigen::Matrix2d mobility = Eigen::Matrix2d::Identity();

  static Track of(const StepStart& start, int i, const Eigen::VectorXd& x, const Eigen::VectorXd& v) {
    return {Path::of(start, i, x, v), x.segment<2>(2 * i), v.segment<2>(2 * i), 0, Eigen::Matrix2d::Identity()};
  }
  Eigen::Vector2d from() const { return path.x0; }
  double t() const { return path.t0; }
};

// Each collider's bounding box (a half-plane's is everything), for a cheap
// rejection of paths that pass nowhere near it.
struct ColliderBoxes {
  std::vector<Eigen::Vector2d> lo, hi;
  explicit ColliderBoxes(const std::vector<Collider>& colliders);

  // Whether the straight path a → b, grown by `margin`, meets any collider's
  // box, or comes within margin of a half-plane: false means it hits nothing.
  bool near(const std::vector<Collider>& colliders, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
            double margin) const {
    const double loX = std::min(a.x(), b.x()) - margin, hiX = std::max(a.x(), b.x()) + margin;
    const double loY = std::min(a.y(), b.y()) - margin, hiY = std::max(a.y(), b.y()) + margin;
    for (std::size_t k = 0; k < lo.size(); ++k) {
      const Collider& c = colliders[k];
      if (c.shape == ColliderShape::HalfPlane) {
        const double offset = c.normal.dot(c.points[0]);
        if (std::min(c.normal.dot(a), c.normal.dot(b)) - offset <= margin) return true;
      } else if (loX <= hi[k].x() && hiX >= lo[k].x() && loY <= hi[k].y() && hiY >= lo[k].y()) {
        return true;
      }
    }
    return false;
  }
};

// Puts p on the collider's surface grown by r, along the surface normal at p.
inline Eigen::Vector2d ontoSurface(const Collider& c, const Eigen::Vector2d& p, double r, Eigen::Vector2d* normal) {
  const SurfaceDistance d = c.distance(p);
  if (normal) *normal = d.normal;
  return p - (d.distance - r) * d.normal;
}

// The next impact of a particle of radius r on its track: the collider, the
// fraction s of the chord from → x1 at which it enters, and the time τ.
struct ColliderImpact {
  int collider = -1;
  double s = std::numeric_limits<double>::infinity();
  double tau = std::numeric_limits<double>::infinity();
};
std::optional<ColliderImpact> nextColliderImpact(const std::vector<Collider>& colliders, const ColliderBoxes& boxes,
                                                 const Track& track, double r, double slop, double dt);
// What an impact did to a track.
enum class ImpactOutcome {
  Bounced,  // the velocity jumped at τ and the track starts there
  Rests,    // the bounce would not clear the surface by the step's end: left for the solver
  Nothing,  // met again at the time of the last event with no change (a grazed corner it leaves)
};
// Applies it when it is a bounce (−e times the normal velocity, Coulomb
// friction along the surface, faster than ContactSettings::
// restitutionThreshold); the track then starts at τ. An impact that
// changes nothing — met again at the time of the last event, with the step's
// end moved by no more than `slop` and its velocity by no more than would move
// it that far in the time left (a corner the chord only grazes, on a face the
// particle is leaving) — is reported as such, since the next search would
// find the same event.
ImpactOutcome applyColliderImpact(const Collider& collider, const ColliderImpact& impact, double r,
                                  const ContactSettings& settings, double dt, Track& track);
// Out of impacts (the work cap ContactSettings::maxImpacts): if the rest of
// the track still enters a collider, its end is put back to its last event,
// which is outside every collider, and true is returned (the step then fails
// with StepFailure::ContactCapReached).
bool stopIfStillEntering(const std::vector<Collider>& colliders, const ColliderBoxes& boxes, double r,
                         double slop, Track& track);

}  // namespace particles::contact
