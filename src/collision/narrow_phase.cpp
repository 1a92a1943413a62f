// The contacts at the step's end, one function per kind (narrow_phase.h).
#include "narrow_phase.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "contact_track.h"
#include "plane_geometry.h"

namespace particles {

namespace {

// The normal row's target of a contact found at positions x with velocities v
// (its gap and normal evaluated there): a bounce for a new contact that
// approaches, from the speed it struck with.
double bounceOf(const NarrowInput& in, Contact& c, double gap, const Eigen::VectorXd& v) {
  if (c.restitution <= 0.0 || in.last.persists(c.key)) return 0.0;
  double un = 0.0, an = 0.0;
  for (int k = 0; k < c.count(); ++k) {
    const int p = c.particle[k];
    const Eigen::Vector2d vp = v.segment<2>(2 * p);
    un += c.beta[k] * c.normal.dot(vp);
    if (in.refs.h[p] > 0.0) an += c.beta[k] * c.normal.dot(vp - in.refs.v.segment<2>(2 * p)) / in.refs.h[p];
  }
  if (!(un < 0.0)) return 0.0;
  const double depth = std::max(0.0, -gap);
  const double impact = std::sqrt(std::max(0.0, un * un + 2.0 * an * depth));
  const double bounce = c.restitution * impact;
  return bounce > in.settings.restitutionThreshold ? bounce : 0.0;
}

void add(const NarrowInput& in, Contact c, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
         std::vector<Contact>& out) {
  const double gap = c.evaluate(x);
  c.bounce = bounceOf(in, c, gap, v);
  out.push_back(c);
}

// Particle i's contact with collider k, with the collider's friction,
// restitution and key; its point and normal are the caller's.
Contact colliderContact(const Collider& collider, int i, int k) {
  Contact c;
  c.kind = ContactKind::Collider;
  c.particle[0] = i;
  c.friction = collider.friction;
  c.restitution = collider.restitution;
  c.key = colliderContactKey(i, k);
  return c;
}

// The contact where the path a → b (of radius r) enters the collider at s:
// the point on its surface and, for a point particle at a corner, the face
// headed into.
void enterAt(const Collider& collider, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double s, double r,
             double slop, Contact& c) {
  c.point = contact::ontoSurface(collider, a + s * (b - a), r, &c.normal);
  if (r == 0.0) c.normal = collider.entryNormal(c.point, b - a, slop);
  c.swept = true;
}

}  // namespace

void colliderContacts(const NarrowInput& in, const std::vector<int>& particles, const Eigen::VectorXd& x,
                      const Eigen::VectorXd& v, std::vector<Contact>& out) {
  const std::vector<Collider>& colliders = in.colliders;
  const contact::ColliderBoxes boxes(colliders);
  const double slop = in.settings.slop;
  for (const int i : particles) {
    if (in.inverseMass[i] == 0.0) continue;
    const double r = in.radius[i];
    const Eigen::Vector2d a = in.refs.x.segment<2>(2 * i), b = x.segment<2>(2 * i);
    if (!boxes.near(colliders, a, b, r + slop)) continue;
    for (int k = 0; k < static_cast<int>(colliders.size()); ++k) {
      const Collider& collider = colliders[k];
      Contact c = colliderContact(collider, i, k);
      if (const std::optional<double> s = collider.sweep(a, b, r, slop)) {
        enterAt(collider, a, b, *s, r, slop, c);
      } else if (collider.distance(b).distance - r <= slop + (in.last.persists(colliderContactKey(i, k)) ? (b - a).norm() : 0.0)) {
        // Touching at the end (or, for a contact of the last step, near
        // enough to touch within another such step: its row holds nothing
        // while open, and keeps its impulses from one step to the next). At a
        // corner of a box or polygon, the face the path heads into; a path
        // that leaves that face is not in contact (two boxes that meet in a
        // seam: the face of one that lies against the other is no surface).
        c.point = contact::ontoSurface(collider, b, r, &c.normal);
        if (r == 0.0) {
          c.normal = collider.entryNormal(c.point, b - a, slop);
          if (c.normal.dot(b - a) > slop) continue;
        }
      } else {
        continue;
      }
      add(in, c, x, v, out);
    }
  }
}

void discPairContacts(const NarrowInput& in, const std::vector<int>& discs,
                      const std::vector<std::pair<int, int>>& pairs, const Eigen::VectorXd& x,
                      const Eigen::VectorXd& v, std::vector<Contact>& out) {
  const double slop = in.settings.slop;
  for (const auto& [a, b] : pairs) {
    const int i = discs[a], j = discs[b];
    if (in.inverseMass[i] + in.inverseMass[j] == 0.0) continue;
    const double reach = in.radius[i] + in.radius[j];
    const Eigen::Vector2d d1 = x.segment<2>(2 * i) - x.segment<2>(2 * j);
    Contact c;
    c.kind = ContactKind::DiscPair;
    c.particle[0] = i;
    c.particle[1] = j;
    c.beta[1] = -1.0;
    c.reach = reach;
    if (d1.squaredNorm() < (reach + slop) * (reach + slop)) {
      c.normal = d1.norm() > 0.0 ? Eigen::Vector2d(d1.normalized()) : Eigen::Vector2d(1.0, 0.0);
    } else {
      // Apart at the end: a contact only if the pair met on the way (its
      // relative chord entered the circle of radius reach).
      const Eigen::Vector2d d0 = in.refs.x.segment<2>(2 * i) - in.refs.x.segment<2>(2 * j);
      const std::optional<double> s = contact::enterCircle(d0, d1 - d0, Eigen::Vector2d::Zero(), reach);
      if (!s) continue;
      c.normal = (d0 + *s * (d1 - d0)).normalized();
      if (c.normal.dot(d1) > 0.0) continue;  // met and left on the same side: no contact at the end
      c.swept = true;
    }
    c.friction = in.settings.particleFriction;
    c.restitution = in.settings.particleRestitution;
    c.key = discPairKey(i, j);
    add(in, c, x, v, out);
  }
}

// The side of the line through a → b (the sign of cross(b − a, ·)) that a
// collider touching it at a corner lies on: where its other corners lie,
// when the line only touches it there (an edge lying on a box's top face
// has the box below it, however the step moved it). A line that cuts the
// collider has no such side; then the side the edge moves towards
// (`motion`, its displacement at the corner over the step) is the corner's.
double colliderSide(const Collider& collider, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                    const Eigen::Vector2d& motion, double slop) {
  const Eigen::Vector2d line = b - a;
  const double touching = slop * line.norm();
  double side = 0.0;
  for (const Eigen::Vector2d& p : collider.points) {
    const double s = cross(line, p - a);
    if (std::abs(s) <= touching) continue;
    if (side == 0.0) {
      side = s;
    } else if ((s > 0.0) != (side > 0.0)) {
      side = 0.0;  // corners on both sides: the line cuts the collider
      break;
    }
  }
  return side != 0.0 ? side : Eigen::Vector2d(-line.y(), line.x()).dot(motion);
}

void edgeCornerContacts(const NarrowInput& in, const std::vector<CollisionEdge>& edges,
                        const std::vector<int>& candidates, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                        std::vector<Contact>& out) {
  const std::vector<Collider>& colliders = in.colliders;
  const contact::ColliderBoxes boxes(colliders);
  const double slop = in.settings.slop;
  const Eigen::VectorXd& S = in.start.x;
  for (const int e : candidates) {
    const int i = edges[e].a, j = edges[e].b;
    if (in.inverseMass[i] + in.inverseMass[j] == 0.0) continue;
    const Eigen::Vector2d si = S.segment<2>(2 * i), sj = S.segment<2>(2 * j);
    const Eigen::Vector2d xi = x.segment<2>(2 * i), xj = x.segment<2>(2 * j);
    const Eigen::Vector2d lo = si.cwiseMin(sj).cwiseMin(xi).cwiseMin(xj), hi = si.cwiseMax(sj).cwiseMax(xi).cwiseMax(xj);
    const Eigen::Vector2d edge = xj - xi;
    const double length2 = edge.squaredNorm();
    if (length2 == 0.0) continue;
    // How far the edge's contacts could turn it over the step: twice its ends' largest move.
    const double speculative = 2.0 * std::max((xi - si).norm(), (xj - sj).norm());
    for (int k = 0; k < static_cast<int>(colliders.size()); ++k) {
      const Collider& collider = colliders[k];
      if (collider.shape == ColliderShape::HalfPlane) continue;  // no corner: its particles keep edges out
      if ((lo.array() > boxes.hi[k].array() + slop).any() || (hi.array() < boxes.lo[k].array() - slop).any()) continue;
      for (int m = 0; m < static_cast<int>(collider.points.size()); ++m) {
        const Eigen::Vector2d& q = collider.points[m];
        const double b = (q - xi).dot(edge) / length2;
        if (!(b > 0.0 && b < 1.0)) continue;  // beyond an end: the end's own contacts hold it
        // The corner's side of the edge: the side of the last solve's
        // contact, which holds the edge there (a step that ended a little
        // past the corner, as an explicit step can, does not turn it over);
        // for a new contact the side at the step's start, and for an edge
        // that starts on the corner (resting on it) the collider's side.
        const std::uint64_t key = edgeCornerKey(e, k, m);
        const Eigen::Vector2d e0 = sj - si;
        double side0 = -in.last.lastSide(key);
        if (side0 == 0.0) {
          side0 = cross(e0, q - si);
          if (std::abs(side0) <= slop * e0.norm())
            side0 = colliderSide(collider, si, sj, (1.0 - b) * (xi - si) + b * (xj - sj), slop);
        }
        if (side0 == 0.0) continue;  // on the edge's line and not moving off it
        Contact c;
        c.kind = ContactKind::EdgeCorner;
        c.particle[0] = i;
        c.particle[1] = j;
        c.point = q;
        c.reach = collider.radius;
        c.side = side0 > 0.0 ? -1.0 : 1.0;
        // Past or within reach of the corner at the end, from the side it
        // started on; or near enough that the solve's turn of the edge about
        // another contact could carry it past (a speculative row: open while
        // the gap stays, pushed out by the projection if the solve closes it).
        const double gap = c.evaluate(x);
        if (gap > slop + speculative) continue;
        c.swept = gap <= slop;
        c.friction = collider.friction;
        c.restitution = collider.restitution;
        c.key = key;
        add(in, c, x, v, out);
      }
    }
  }
}

int missedContacts(const NarrowInput& in, const std::vector<int>& particles, const std::vector<int>& discs,
                   const std::vector<std::pair<int, int>>& pairs, const Eigen::VectorXd& x,
                   const Eigen::VectorXd& before, std::vector<Contact>& found) {
  std::vector<std::uint64_t> keys(found.size());
  for (std::size_t k = 0; k < found.size(); ++k) keys[k] = found[k].key;
  std::sort(keys.begin(), keys.end());
  const auto known = [&](std::uint64_t key) { return std::binary_search(keys.begin(), keys.end(), key); };
  const std::size_t count = found.size();
  const std::vector<Collider>& colliders = in.colliders;
  const contact::ColliderBoxes boxes(colliders);
  const double slop = in.settings.slop;
  for (const int i : particles) {
    if (in.inverseMass[i] == 0.0) continue;
    const double r = in.radius[i];
    const Eigen::Vector2d a = in.refs.x.segment<2>(2 * i), b = x.segment<2>(2 * i);
    if (colliders.empty() || !boxes.near(colliders, a, b, r + slop)) continue;
    for (int k = 0; k < static_cast<int>(colliders.size()); ++k) {
      if (known(colliderContactKey(i, k))) continue;
      const std::optional<double> s = colliders[k].sweep(a, b, r, slop);
      if (!s) continue;
      Contact c = colliderContact(colliders[k], i, k);
      enterAt(colliders[k], a, b, *s, r, slop, c);
      add(in, c, x, before, found);
    }
  }
  for (const auto& [a, b] : pairs) {
    const int i = discs[a], j = discs[b];
    if (in.inverseMass[i] + in.inverseMass[j] == 0.0 || known(discPairKey(i, j))) continue;
    const double reach = in.radius[i] + in.radius[j];
    const Eigen::Vector2d d = x.segment<2>(2 * i) - x.segment<2>(2 * j);
    if (!(d.squaredNorm() < (reach - slop) * (reach - slop))) continue;
    Contact c;
    c.kind = ContactKind::DiscPair;
    c.particle[0] = i;
    c.particle[1] = j;
    c.beta[1] = -1.0;
    c.reach = reach;
    c.normal = d.norm() > 0.0 ? Eigen::Vector2d(d.normalized()) : Eigen::Vector2d(1.0, 0.0);
    c.swept = true;
    c.friction = in.settings.particleFriction;
    c.restitution = in.settings.particleRestitution;
    c.key = discPairKey(i, j);
    add(in, c, x, before, found);
  }
  return static_cast<int>(found.size() - count);
}

}  // namespace particles
