// Bounces at their exact times (impacts.h): points one impact after another,
// discs through an event queue.
#include "impacts.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "contact_track.h"
#include "particles/cancel.h"

namespace particles {

using contact::ontoSurface;

void References::reset(const StepStart& start) {
  x = start.x;
  v = start.v;
  h.setConstant(start.x.size() / 2, start.dt);
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

// A pair impact: equal and opposite velocity changes along n at τ.
struct PairImpact {
  double tau = 0.0;
  Eigen::Vector2d n = Eigen::Vector2d::Zero();
  double dv = 0.0;  // change of the relative normal velocity
};

// The first bounce of discs i and j on their tracks, if any. Both tracks hold
// from the later of their last events, t0.
std::optional<PairImpact> nextPairImpact(const contact::Track& ti, const contact::Track& tj, double reach,
                                         const ContactSettings& settings, double dt) {
  const double slop = settings.slop, restitution = settings.particleRestitution;
  const double t0 = std::max(ti.t(), tj.t()), span = dt - t0;
  const Eigen::Vector2d d0 = ti.path.position(t0) - tj.path.position(t0), d1 = ti.x1 - tj.x1;
  // Apart at t0: the relative chord d0 → d1 (exact when both accelerate
  // alike, as in a uniform field) meets |d| = reach at s, the time of impact
  // t0 + s·(dt − t0). Touching or overlapping at t0 (a third disc pushed one
  // into the other): s = 0.
  // (A gap within the slop counts as touching: the chord entering the circle
  // of radius reach + slop strikes, so a pair that closes to within round-off
  // of touching at the step's end strikes there.)
  std::optional<double> s = 0.0;
  if (d0.norm() - reach > slop) s = contact::enterCircle(d0, d1 - d0, Eigen::Vector2d::Zero(), reach + slop);
  if (!s) return std::nullopt;
  const double tau = t0 + *s * span, remaining = dt - tau;
  const Eigen::Vector2d dTau = d0 + *s * (d1 - d0);
  const Eigen::Vector2d n = dTau.norm() > 0.0 ? Eigen::Vector2d(dTau.normalized()) : Eigen::Vector2d(1, 0);
  const double un = (ti.path.velocity(tau) - tj.path.velocity(tau)).dot(n);
  const Eigen::Vector2d ai = ti.path.a, aj = tj.path.a;
  const contact::NormalChange change = contact::normalChange(un, (ai - aj).dot(n), remaining, restitution);
  // Touching at t0, an approach slower than the accelerations bring in a step
  // is a resting contact pressed on (a stack), not an impact.
  const double settled = slop / dt;
  const double resting = *s > 0.0 ? settled : std::max(settled, (ai.norm() + aj.norm()) * dt);
  if (!(un < -resting) || change.resting || change.dv + un < settings.restitutionThreshold) return std::nullopt;
  return PairImpact{tau, n, change.dv};
}

// Equal and opposite impulses P at τ: each disc's velocity jumps by Δv there
// and the rest of its path, and so the step's end, is displaced by Δv (dt − τ).
void applyPairImpact(const PairImpact& impact, double wi, double wj, double dt, contact::Track& ti,
                     contact::Track& tj) {
  // Each disc moves along P n (its constraints take the rest of an impulse along n).
  const Eigen::Vector2d& n = impact.n;
  const double impulse = impact.dv / (wi * n.dot(ti.mobility * n) + wj * n.dot(tj.mobility * n));
  auto kick = [&](contact::Track& t, const Eigen::Vector2d& dv) {
    if (dv.isZero(0.0)) return;  // a pinned disc
    t.path = {t.path.position(impact.tau), t.path.velocity(impact.tau) + dv, t.path.a, impact.tau};
    t.v1 += dv;
    t.x1 = t.path.position(dt);
    ++t.impacts;
  };
  kick(ti, impulse * wi * (ti.mobility * n));
  kick(tj, -impulse * wj * (tj.mobility * n));
}

// Particle i's track, with its constraints' mobility if it is anchored.
contact::Track trackOf(const StepStart& start, int i, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                       const std::vector<Anchored>& anchored) {
  contact::Track track = contact::Track::of(start, i, x, v);
  const auto found = std::lower_bound(anchored.begin(), anchored.end(), i,
                                      [](const Anchored& a, int particle) { return a.particle < particle; });
  if (found != anchored.end() && found->particle == i) track.mobility = found->mobility;
  return track;
}

// The track's end and, if it met anything, its reference (its last impact).
void finish(const contact::Track& track, int i, double dt, Eigen::VectorXd& x, Eigen::VectorXd& v,
            References& refs) {
  x.segment<2>(2 * i) = track.x1;
  v.segment<2>(2 * i) = track.v1;
  if (track.impacts == 0) return;
  refs.x.segment<2>(2 * i) = track.path.x0;
  refs.v.segment<2>(2 * i) = track.path.u0;
  refs.h[i] = dt - track.path.t0;
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

ImpactOutcome applyColliderImpact(const Collider& c, const ColliderImpact& impact, double r,
                                  const ContactSettings& settings, double dt, Track& track) {
  const double slop = settings.slop;
  const double t = track.t();
  const Eigen::Vector2d x1Before = track.x1, v1Before = track.v1;
  const Eigen::Vector2d from = track.from();
  Path& path = track.path;
  const double tau = impact.tau;
  // The face entered is the one under the chord's entry point; the contact
  // point is the curved path's point at τ, put on that face's plane.
  Eigen::Vector2d normal;
  const Eigen::Vector2d entry = ontoSurface(c, from + impact.s * (track.x1 - from), r, &normal);
  if (r == 0.0) normal = c.entryNormal(entry, track.x1 - from, slop);  // a corner: the face the chord goes into
  const Eigen::Vector2d q = path.position(tau), p = q - normal.dot(q - entry) * normal;
  const Eigen::Vector2d u = path.velocity(tau);
  const double un = u.dot(normal), remaining = dt - tau;
  const NormalChange change = normalChange(un, path.a.dot(normal), remaining, c.restitution);
  // A bounce slower than the threshold rests (a pile's contacts, pressed by
  // a step's gravity, are held, not bounced).
  if (change.resting || change.dv + un < settings.restitutionThreshold) return ImpactOutcome::Rests;
  // An impulse at τ: the velocity jumps by Δv there and the rest of the
  // path, and so the step's end, is displaced by Δv·(dt − τ). Held by
  // constraints, the particle moves along P n: the impulse that changes its
  // normal speed by Δv_n is Δv_n / (nᵀ P n) along it.
  const Eigen::Matrix2d& P = track.mobility;
  const double along = normal.dot(P * normal);
  if (!(along > 1e-12)) return ImpactOutcome::Rests;  // its constraints hold it against the face
  const Eigen::Vector2d dv =
      P * (normal * (change.dv / along) + coulomb(u - un * normal, change.dv / along, c.friction));
  path = {p, u + dv, path.a, tau};
  track.v1 += dv;
  track.x1 = path.position(dt);
  ++track.impacts;
  const bool nothing = tau == t && (track.x1 - x1Before).norm() <= slop &&
                       (track.v1 - v1Before).norm() * remaining <= slop;
  return nothing ? ImpactOutcome::Nothing : ImpactOutcome::Bounced;
}

bool stopIfStillEntering(const std::vector<Collider>& colliders, const ColliderBoxes& boxes, double r,
                         double slop, Track& track) {
  if (firstHit(colliders, boxes, track.from(), track.x1, r, slop).collider < 0) return false;
  track.x1 = track.from();
  return true;
}

}  // namespace contact

struct Impacts::Scratch {
  // Each disc's track and stamp (its impacts so far), the predicted events.
  struct Event {
    double tau;
    int a, b;  // discs (indices into the list); b < 0 for a collider impact
    int stampA, stampB;
    contact::ColliderImpact wall;
    PairImpact pair;
  };
  std::vector<contact::Track> tracks;
  std::vector<int> stamp;
  std::vector<char> resting;           // a disc resting on a collider: no more collider impacts
  std::vector<int> pairsOfStart, pairsOf, fill;  // each disc's pairs (compressed rows)
  std::vector<Event> queue;            // a min-heap on tau
};

Impacts::Impacts() : scratch_(std::make_unique<Scratch>()) {}
Impacts::~Impacts() = default;
Impacts::Impacts(Impacts&&) noexcept = default;
Impacts& Impacts::operator=(Impacts&&) noexcept = default;

ContactCount Impacts::resolve(const std::vector<Collider>& colliders, const std::vector<int>& points,
                              const std::vector<int>& discs, const std::vector<std::pair<int, int>>& pairs,
                              const std::vector<Anchored>& anchored, const StepStart& start,
                              const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                              const ContactSettings& settings, Eigen::VectorXd& x, Eigen::VectorXd& v,
                              References& refs) {
  ContactCount counted;
  if (!colliders.empty())
    counted += resolvePoints(colliders, points, anchored, start, inverseMass, radius, settings, x, v, refs);
  if (!discs.empty())
    counted += resolveDiscs(colliders, discs, pairs, anchored, start, inverseMass, radius, settings, x, v, refs);
  return counted;
}

// Points meet only colliders: each one's impacts one after another.
ContactCount Impacts::resolvePoints(const std::vector<Collider>& colliders, const std::vector<int>& points,
                                    const std::vector<Anchored>& anchored, const StepStart& start, const Eigen::VectorXd& inverseMass,
                                    const Eigen::VectorXd& radius, const ContactSettings& settings,
                                    Eigen::VectorXd& x, Eigen::VectorXd& v, References& refs) {
  const double dt = start.dt;
  const contact::ColliderBoxes boxes(colliders);
  ContactCount counted;
  // A particle's impacts may be thousands (ContactSettings::maxImpacts):
  // the flag is read every 64 of them.
  CancelPoll cancel(64);
  for (const int i : points) {
    if (cancel.poll()) break;
    if (inverseMass[i] == 0.0) continue;
    const double r = radius[i];
    if (!boxes.near(colliders, start.x.segment<2>(2 * i), x.segment<2>(2 * i), r + settings.slop)) continue;
    contact::Track track = trackOf(start, i, x, v, anchored);
    while (track.impacts < settings.maxImpacts && !cancel.poll()) {
      const std::optional<contact::ColliderImpact> impact =
          contact::nextColliderImpact(colliders, boxes, track, r, settings.slop, dt);
      if (!impact) break;
      const auto outcome = contact::applyColliderImpact(colliders[impact->collider], *impact, r, settings, dt, track);
      if (outcome != contact::ImpactOutcome::Bounced) break;
    }
    if (track.impacts == settings.maxImpacts && contact::stopIfStillEntering(colliders, boxes, r, settings.slop, track))
      ++counted.capped;
    counted.contacts += track.impacts;
    finish(track, i, dt, x, v, refs);
  }
  return counted;
}

// Discs meet colliders and each other: every disc's next impact is predicted
// on its track and the earliest is applied first, so each impact happens on
// the paths the discs really follow then. An impact changes the tracks of its
// discs only; the predictions that involve them are made again (older ones in
// the queue are recognised as stale by the discs' stamps). Each disc takes at
// most maxImpacts impacts (the work cap): one that would take more is counted
// in `capped`.
ContactCount Impacts::resolveDiscs(const std::vector<Collider>& colliders, const std::vector<int>& discs,
                                   const std::vector<std::pair<int, int>>& pairs,
                                   const std::vector<Anchored>& anchored, const StepStart& start,
                                   const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                                   const ContactSettings& settings, Eigen::VectorXd& x, Eigen::VectorXd& v,
                                   References& refs) {
  Scratch& S = *scratch_;
  const int count = static_cast<int>(discs.size());
  const double dt = start.dt;
  const contact::ColliderBoxes boxes(colliders);
  S.tracks.resize(count);
  S.stamp.assign(count, 0);
  S.resting.assign(count, 0);
  for (int a = 0; a < count; ++a) S.tracks[a] = trackOf(start, discs[a], x, v, anchored);
  S.pairsOfStart.assign(count + 1, 0);
  for (const auto& [a, b] : pairs) ++S.pairsOfStart[a + 1], ++S.pairsOfStart[b + 1];
  for (int a = 0; a < count; ++a) S.pairsOfStart[a + 1] += S.pairsOfStart[a];
  S.pairsOf.resize(S.pairsOfStart[count]);
  S.fill.assign(S.pairsOfStart.begin(), S.pairsOfStart.end() - 1);
  for (int p = 0; p < static_cast<int>(pairs.size()); ++p) {
    S.pairsOf[S.fill[pairs[p].first]++] = p;
    S.pairsOf[S.fill[pairs[p].second]++] = p;
  }

  S.queue.clear();
  auto later = [](const Scratch::Event& e, const Scratch::Event& f) { return e.tau > f.tau; };
  auto push = [&](const Scratch::Event& e) {
    S.queue.push_back(e);
    std::push_heap(S.queue.begin(), S.queue.end(), later);
  };
  auto movable = [&](int a) { return inverseMass[discs[a]] > 0.0 && S.tracks[a].impacts < settings.maxImpacts; };
  auto predictWall = [&](int a) {
    if (colliders.empty() || S.resting[a] || !movable(a)) return;
    const std::optional<contact::ColliderImpact> hit =
        contact::nextColliderImpact(colliders, boxes, S.tracks[a], radius[discs[a]], settings.slop, dt);
    if (hit) push({hit->tau, a, -1, S.stamp[a], 0, *hit, {}});
  };
  auto predictPair = [&](int p) {
    const auto [a, b] = pairs[p];
    if (inverseMass[discs[a]] + inverseMass[discs[b]] == 0.0) return;
    if (S.tracks[a].impacts >= settings.maxImpacts || S.tracks[b].impacts >= settings.maxImpacts) return;
    const std::optional<PairImpact> hit =
        nextPairImpact(S.tracks[a], S.tracks[b], radius[discs[a]] + radius[discs[b]], settings, dt);
    if (hit) push({hit->tau, a, b, S.stamp[a], S.stamp[b], {}, *hit});
  };
  auto predictPairsOf = [&](int a) {
    for (int k = S.pairsOfStart[a]; k < S.pairsOfStart[a + 1]; ++k) predictPair(S.pairsOf[k]);
  };
  for (int a = 0; a < count; ++a) predictWall(a);
  for (int p = 0; p < static_cast<int>(pairs.size()); ++p) predictPair(p);

  ContactCount counted;
  CancelPoll cancel(64);
  while (!S.queue.empty() && !cancel.poll()) {
    std::pop_heap(S.queue.begin(), S.queue.end(), later);
    const Scratch::Event e = S.queue.back();
    S.queue.pop_back();
    if (e.stampA != S.stamp[e.a] || (e.b >= 0 && e.stampB != S.stamp[e.b])) continue;  // stale
    if (e.b < 0) {
      const contact::ImpactOutcome outcome = contact::applyColliderImpact(colliders[e.wall.collider], e.wall, radius[discs[e.a]], settings, dt, S.tracks[e.a]);
      if (outcome == contact::ImpactOutcome::Rests) {
        S.resting[e.a] = 1;  // the solver holds it there; its pairs may still strike
        continue;
      }
      ++counted.contacts;
      ++S.stamp[e.a];
      // A grazed corner changes nothing: only the disc's pairs are predicted again.
      if (outcome == contact::ImpactOutcome::Bounced) predictWall(e.a);
      predictPairsOf(e.a);
    } else {
      ++counted.contacts;
      ++S.stamp[e.a];
      ++S.stamp[e.b];
      applyPairImpact(e.pair, inverseMass[discs[e.a]], inverseMass[discs[e.b]], dt, S.tracks[e.a], S.tracks[e.b]);
      for (const int d : {e.a, e.b}) {
        S.resting[d] = 0;  // its path changed: it may meet a collider anew
        predictWall(d);
        predictPairsOf(d);
      }
    }
  }

  for (int a = 0; a < count; ++a) {
    contact::Track& track = S.tracks[a];
    if (track.impacts >= settings.maxImpacts &&
        (colliders.empty() || contact::stopIfStillEntering(colliders, boxes, radius[discs[a]], settings.slop, track)))
      ++counted.capped;
    finish(track, discs[a], dt, x, v, refs);
  }
  return counted;
}

}  // namespace particles
