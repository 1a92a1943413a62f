// Particles against colliders: continuous detection along the step's path,
// impacts with restitution and Coulomb friction, resting contact.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "contact_track.h"
#include "particles/check.h"
#include "collider_contacts.h"

namespace particles {

using contact::ontoSurface;

void ContactSettings::validate() const {
  if (iterations < 1 || iterations > 1000)
    throw std::invalid_argument("contact iterations must be in [1, 1000], got " + std::to_string(iterations));
  if (maxImpacts < 1 || maxImpacts > 1000000000)
    throw std::invalid_argument("contact maxImpacts must be in [1, 1000000000], got " + std::to_string(maxImpacts));
  requireNonNegative("contact slop", slop);
  if (coupledIterations < 1 || coupledIterations > 100000)
    throw std::invalid_argument("contact coupledIterations must be in [1, 100000], got " +
                                std::to_string(coupledIterations));
  if (positionIterations < 1 || positionIterations > 100000)
    throw std::invalid_argument("contact positionIterations must be in [1, 100000], got " +
                                std::to_string(positionIterations));
  requireNonNegative("contact coupledTolerance", coupledTolerance);
  requireNonNegative("contact restitutionThreshold", restitutionThreshold);
  requireInRange("particle contact restitution", particleRestitution, 0.0, 1.0);
}

namespace {

struct Hit {
  int collider = -1;
  double s = std::numeric_limits<double>::infinity();  // fraction of the swept segment
};

// The first collider the straight path a → b enters (grown by the particle's radius r).
Hit firstHit(const std::vector<Collider>& colliders, const contact::ColliderBoxes& boxes, const Eigen::Vector2d& a,
             const Eigen::Vector2d& b, double r, double slop) {
  const Eigen::Vector2d pathLo = a.cwiseMin(b).array() - (r + slop), pathHi = a.cwiseMax(b).array() + (r + slop);
  Hit hit;
  for (int k = 0; k < static_cast<int>(colliders.size()); ++k) {
    if ((pathLo.array() > boxes.hi[k].array()).any() || (pathHi.array() < boxes.lo[k].array()).any()) continue;
    if (const std::optional<double> s = colliders[k].sweep(a, b, r, slop))
      if (*s < hit.s) hit = {k, *s};
  }
  return hit;
}

// The time the curved path reaches the surface, refined by Newton's method on
// f(τ) = distance(q(τ)) − r from the time the straight chord reaches it; the
// chord's time is kept when the iteration leaves [from, dt] or does not settle.
double impactTime(const Collider& c, const contact::Path& path, double r, double chordTime, double from,
                  double dt) {
  double t = chordTime;
  for (int k = 0; k < 4; ++k) {
    const SurfaceDistance d = c.distance(path.position(t));
    const double slope = d.normal.dot(path.velocity(t));
    if (!(slope < 0.0)) return chordTime;
    t -= (d.distance - r) / slope;
    if (!(t >= from && t <= dt)) return chordTime;
  }
  return t;
}

}  // namespace

namespace contact {

ColliderBoxes::ColliderBoxes(const std::vector<Collider>& colliders) : lo(colliders.size()), hi(colliders.size()) {
  for (std::size_t k = 0; k < colliders.size(); ++k)
    if (!colliders[k].bounds(lo[k], hi[k])) {
      lo[k].setConstant(-std::numeric_limits<double>::infinity());
      hi[k].setConstant(std::numeric_limits<double>::infinity());
    }
}

std::optional<ColliderImpact> nextColliderImpact(const std::vector<Collider>& colliders, const ColliderBoxes& boxes,
                                                 const Track& track, double r, double slop, double dt) {
  const double t = track.t();
  const Hit hit = firstHit(colliders, boxes, track.from(), track.x1, r, slop);
  if (hit.collider < 0) return std::nullopt;
  const double chordTime = t + hit.s * (dt - t);
  const double tau = hit.s > 0.0 ? impactTime(colliders[hit.collider], track.path, r, chordTime, t, dt) : t;
  return ColliderImpact{hit.collider, hit.s, tau};
}

bool applyColliderImpact(const Collider& c, const ColliderImpact& impact, double r, double slop, double dt,
                         Track& track) {
  const double t = track.t();
  const Eigen::Vector2d x1Before = track.x1, v1Before = track.v1;
  const Eigen::Vector2d from = track.from();
  contact::Path& path = track.path;
  Eigen::Vector2d &x1 = track.x1, &v1 = track.v1;
  const double tau = impact.tau;
  // The face entered is the one under the chord's entry point; the contact
  // point is the curved path's point at τ, put on that face's plane.
  Eigen::Vector2d normal;
  const Eigen::Vector2d entry = ontoSurface(c, from + impact.s * (x1 - from), r, &normal);
  if (r == 0.0) normal = c.entryNormal(entry, x1 - from, slop);  // a corner: the face the chord goes into
  const Eigen::Vector2d q = path.position(tau), p = q - normal.dot(q - entry) * normal;
  const Eigen::Vector2d u = path.velocity(tau);
  const double un = u.dot(normal), remaining = dt - tau;
  const NormalChange change = normalChange(un, path.a.dot(normal), remaining, c.restitution);
  if (!change.resting) {
    // An impulse at τ: the velocity jumps by Δv there and the rest of the
    // path, and so the step's end, is displaced by Δv·(dt − τ).
    const Eigen::Vector2d dv = change.dv * normal + coulomb(u - un * normal, change.dv, c.friction);
    path = {p, u + dv, path.a, tau};
    v1 += dv;
    x1 = path.position(dt);
  } else {
    // Resting for the rest of the step: the normal impulse cancels the
    // normal velocity at the end (for a particle at rest, its weight × dt).
    // Friction that stops the tangential motion inside the cone (static) holds
    // the particle where it met the face: the end keeps only its normal offset
    // from p, whatever the scheme's position update added along the face (a
    // symplectic or implicit update moves a resting particle by a dt² along
    // it while the velocity it reports is 0). Sliding friction, spread evenly
    // over the time left, moves the end by ½ Δv_t (dt − τ).
    const double v1n = v1.dot(normal), dvn = std::max(0.0, -v1n);
    const Eigen::Vector2d vt = v1 - v1n * normal;
    const Eigen::Vector2d dvt = coulomb(vt, dvn, c.friction);
    // Static: the cone holds both the tangential speed at the end and the one
    // the particle met the face with.
    const double holds = c.friction * dvn;
    const bool sticks = c.friction > 0.0 && vt.norm() <= holds && (u - un * normal).norm() <= holds;
    v1 += dvn * normal + dvt;
    if (sticks)
      x1 = p + normal.dot(x1 - p) * normal;
    else
      x1 += 0.5 * remaining * dvt;
    // Back onto the surface. At a corner of a box or polygon the nearest
    // surface point may lie on the other face, which would leave the particle
    // off the face it rests on, to meet that again at once: it backs out along
    // the normal of the face it rests on instead.
    if (c.distance(x1).distance < r) {
      const bool flat = r == 0.0 && c.radius == 0.0 && c.points.size() >= 3;  // a box or polygon
      x1 = flat ? Eigen::Vector2d(x1 + std::max(0.0, normal.dot(entry - x1)) * normal) : ontoSurface(c, x1, r, nullptr);
    }
    path = remaining > 0.0 ? Path{p, (x1 - p) / remaining - 0.5 * path.a * remaining, path.a, tau}
                           : Path{p, v1, path.a, tau};
  }
  ++track.impacts;
  return !(tau == t && (x1 - x1Before).norm() <= slop && (v1 - v1Before).norm() * remaining <= slop);
}

bool stopIfStillEntering(const std::vector<Collider>& colliders, const ColliderBoxes& boxes, double r,
                         double slop, Track& track) {
  if (firstHit(colliders, boxes, track.from(), track.x1, r, slop).collider < 0) return false;
  track.x1 = track.from();
  return true;
}

}  // namespace contact

ContactCount resolveColliderContacts(const std::vector<Collider>& colliders, const StepStart& start,
                                     const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                                     const ContactSettings& settings, Eigen::VectorXd& x, Eigen::VectorXd& v,
                                     Eigen::VectorXd& lastFree, const std::vector<int>* only) {
  const double dt = start.dt;
  const int n = static_cast<int>(inverseMass.size());
  const contact::ColliderBoxes boxes(colliders);
  if (lastFree.size() != x.size()) lastFree = x;
  ContactCount contacts;
  const int count = only ? static_cast<int>(only->size()) : n;
  for (int k = 0; k < count; ++k) {
    const int i = only ? (*only)[k] : k;
    lastFree.segment<2>(2 * i) = x.segment<2>(2 * i);
    if (inverseMass[i] == 0.0) continue;
    const double r = radius[i];
    if (!boxes.near(colliders, start.x.segment<2>(2 * i), x.segment<2>(2 * i), r + settings.slop)) continue;
    contact::Track track = contact::Track::of(start, i, x, v);
    while (track.impacts < settings.maxImpacts) {
      const std::optional<contact::ColliderImpact> impact =
          contact::nextColliderImpact(colliders, boxes, track, r, settings.slop, dt);
      if (!impact) break;
      if (!contact::applyColliderImpact(colliders[impact->collider], *impact, r, settings.slop, dt, track)) break;
    }
    if (track.impacts == settings.maxImpacts && contact::stopIfStillEntering(colliders, boxes, r, settings.slop, track))
      ++contacts.capped;
    contacts.contacts += track.impacts;
    x.segment<2>(2 * i) = track.x1;
    v.segment<2>(2 * i) = track.v1;
    lastFree.segment<2>(2 * i) = track.x1;
  }
  return contacts;
}

ContactCount pushOutOfColliders(const std::vector<Collider>& colliders, const Eigen::VectorXd& inverseMass,
                                const Eigen::VectorXd& radius, const ContactSettings& settings, Eigen::VectorXd& x,
                                Eigen::VectorXd& v, Eigen::VectorXd& lastFree) {
  const int n = static_cast<int>(inverseMass.size());
  const contact::ColliderBoxes boxes(colliders);
  ContactCount contacts;
  for (int i = 0; i < n; ++i) {
    if (inverseMass[i] == 0.0) continue;
    const double r = radius[i];
    Eigen::Vector2d x1 = x.segment<2>(2 * i), v1 = v.segment<2>(2 * i);
    Eigen::Vector2d from = lastFree.segment<2>(2 * i);
    if (from == x1) continue;  // not moved since it was known to be outside
    int pass = 0;
    for (; pass < settings.maxImpacts; ++pass) {
      const Hit hit = firstHit(colliders, boxes, from, x1, r, settings.slop);
      if (hit.collider < 0) break;
      const Collider& c = colliders[hit.collider];
      // The face entered on the way from the last free position: back onto
      // it along its normal, the approach removed, Coulomb friction applied.
      Eigen::Vector2d normal;
      const Eigen::Vector2d p = ontoSurface(c, from + hit.s * (x1 - from), r, &normal);
      x1 += std::max(0.0, normal.dot(p - x1)) * normal;
      const double vn = v1.dot(normal);
      if (vn < 0.0) v1 += -vn * normal + contact::coulomb(v1 - vn * normal, vn, c.friction);
      from = p;
      ++contacts.contacts;
    }
    if (pass == settings.maxImpacts && firstHit(colliders, boxes, from, x1, r, settings.slop).collider >= 0) {
      x1 = from;  // out of passes: back to the last point known outside
      ++contacts.capped;
    }
    x.segment<2>(2 * i) = x1;
    v.segment<2>(2 * i) = v1;
    lastFree.segment<2>(2 * i) = x1;
  }
  return contacts;
}

}  // namespace particles
