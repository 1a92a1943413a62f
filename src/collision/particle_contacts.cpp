// Disc–disc contacts: a uniform-grid broad phase, impacts against each other
// and against colliders taken in the order of their times, resting pairs split
// by inverse mass.
#include <algorithm>
#include <cmath>

#include "contact_track.h"
#include "particles/check.h"
#include "particle_contacts.h"

namespace particles {

namespace {

// A resting (or overlapping) pair at the step's end: the overlap split in
// proportion to inverse mass, the approach along the line of centres removed.
// Returns the speed change, or −1 when the pair is apart.
double restingPair(int i, int j, const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                   const ContactSettings& settings, Eigen::VectorXd& x, Eigen::VectorXd& v) {
  const double wi = inverseMass[i], wj = inverseMass[j], wsum = wi + wj;
  const double reach = radius[i] + radius[j];
  const Eigen::Vector2d d = x.segment<2>(2 * i) - x.segment<2>(2 * j);
  const double dist2 = d.squaredNorm();
  if (wsum == 0.0 || dist2 >= (reach - settings.slop) * (reach - settings.slop)) return -1.0;
  const double dist = std::sqrt(dist2);
  const Eigen::Vector2d n = dist > 0.0 ? Eigen::Vector2d(d / dist) : Eigen::Vector2d(1.0, 0.0);
  const double overlap = reach - dist;
  x.segment<2>(2 * i) += (overlap * wi / wsum) * n;
  x.segment<2>(2 * j) -= (overlap * wj / wsum) * n;
  const double vn = (v.segment<2>(2 * i) - v.segment<2>(2 * j)).dot(n);
  if (!(vn < 0.0)) return 0.0;
  const double impulse = -vn / wsum;
  v.segment<2>(2 * i) += impulse * wi * n;
  v.segment<2>(2 * j) -= impulse * wj * n;
  return -vn;
}

// A pair impact: equal and opposite velocity changes along n at τ.
struct PairImpact {
  double tau = 0.0;
  Eigen::Vector2d n = Eigen::Vector2d::Zero();
  double dv = 0.0;  // change of the relative normal velocity
};

// The first impact of discs i and j on their tracks, if any. Both tracks hold
// from the later of their last events, t0.
std::optional<PairImpact> nextPairImpact(const contact::Track& ti, const contact::Track& tj, double reach,
                                         double restitution, double slop, double dt) {
  const double t0 = std::max(ti.t(), tj.t()), span = dt - t0;
  const Eigen::Vector2d d0 = ti.path.position(t0) - tj.path.position(t0), d1 = ti.x1 - tj.x1;
  // Apart at t0: the relative chord d0 → d1 (exact when both accelerate
  // alike, as in a uniform field) meets |d| = reach at s, the time of impact
  // t0 + s·(dt − t0). Touching or overlapping at t0 (a third disc pushed one
  // into the other): s = 0.
  std::optional<double> s = 0.0;
  if (d0.norm() - reach > slop) s = contact::enterCircle(d0, d1 - d0, Eigen::Vector2d::Zero(), reach);
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
  if (!(un < -resting) || change.resting) return std::nullopt;
  return PairImpact{tau, n, change.dv};
}

// Equal and opposite impulses P at τ: each disc's velocity jumps by Δv there
// and the rest of its path, and so the step's end, is displaced by Δv (dt − τ).
void applyPairImpact(const PairImpact& impact, double wi, double wj, double dt, contact::Track& ti,
                     contact::Track& tj) {
  const double impulse = impact.dv / (wi + wj);
  auto kick = [&](contact::Track& t, const Eigen::Vector2d& dv) {
    if (dv.isZero(0.0)) return;  // a pinned disc
    t.path = {t.path.position(impact.tau), t.path.velocity(impact.tau) + dv, t.path.a, impact.tau};
    t.v1 += dv;
    t.x1 = t.path.position(dt);
    ++t.impacts;
  };
  kick(ti, impulse * wi * impact.n);
  kick(tj, -impulse * wj * impact.n);
}

}  // namespace

struct ParticleContacts::Scratch {
  // Broad phase: each disc's cell and bucket, discs sorted by bucket, the candidate pairs.
  std::vector<Eigen::Vector2i> cells;
  std::vector<int> bucket, order, bucketStart, fill;
  std::vector<std::pair<int, int>> pairs;
  std::vector<int> pairsOfStart, pairsOf;  // each disc's candidate pairs (compressed rows)
  // Impacts: each disc's track and stamp (its impacts so far), the predicted events.
  struct Event {
    double tau;
    int a, b;  // discs (indices into collidable); b < 0 for a collider impact
    int stampA, stampB;
    contact::ColliderImpact wall;
    PairImpact pair;
  };
  std::vector<contact::Track> tracks;
  std::vector<int> stamp;
  std::vector<Event> queue;  // a min-heap on tau
};

ParticleContacts::ParticleContacts() : scratch_(std::make_unique<Scratch>()) {}
ParticleContacts::~ParticleContacts() = default;
ParticleContacts::ParticleContacts(ParticleContacts&&) noexcept = default;
ParticleContacts& ParticleContacts::operator=(ParticleContacts&&) noexcept = default;

ContactCount ParticleContacts::resolve(const std::vector<int>& collidable, const std::vector<Collider>& colliders,
                                       const StepStart& start, const Eigen::VectorXd& inverseMass,
                                       const Eigen::VectorXd& radius, const ContactSettings& settings, bool impacts,
                                       Eigen::VectorXd& x, Eigen::VectorXd& v, Eigen::VectorXd* lastFree) {
  const Scratch& S = *scratch_;
  const int count = static_cast<int>(collidable.size());
  touching_.clear();
  if (count == 0) return {};
  double maxRadius = 0.0, maxTravel = 0.0;
  for (int i : collidable) {
    maxRadius = std::max(maxRadius, radius[i]);
    if (impacts) maxTravel = std::max(maxTravel, (x.segment<2>(2 * i) - start.x.segment<2>(2 * i)).norm());
  }
  // Broad phase on the positions at the step's start (or its end without
  // impacts). A disc stays within twice its free travel of its start (impacts
  // turn it, and between comparable masses do not much speed it up), so any
  // pair that touches during the step lies in neighbouring cells.
  const Eigen::VectorXd& at = impacts ? start.x : x;
  findCandidatePairs(collidable, at, 2.0 * (maxRadius + 2.0 * maxTravel));

  ContactCount contacts;
  if (impacts) contacts += resolveImpacts(collidable, colliders, start, inverseMass, radius, settings, x, v, lastFree);

  // What is left touching or overlapping at the end is resting contact.
  for (const auto& [a, b] : S.pairs) {
    const int i = collidable[a], j = collidable[b];
    const double reach = radius[i] + radius[j];
    if (inverseMass[i] + inverseMass[j] == 0.0 ||
        (x.segment<2>(2 * i) - x.segment<2>(2 * j)).squaredNorm() >= (reach + settings.slop) * (reach + settings.slop))
      continue;
    touching_.emplace_back(i, j);
    if (restingPair(i, j, inverseMass, radius, settings, x, v) >= 0.0) ++contacts.contacts;
  }
  return contacts;
}

void ParticleContacts::findCandidatePairs(const std::vector<int>& collidable, const Eigen::VectorXd& x,
                                          double cell) {
  Scratch& S = *scratch_;
  S.pairs.clear();
  const int count = static_cast<int>(collidable.size());
  if (count < 2 || !(cell > 0.0) || !std::isfinite(cell)) return;
  // Hash each disc's cell into a table of 2·count buckets, and sort discs by
  // bucket (counting sort, linear time).
  int buckets = 1;
  while (buckets < 2 * count) buckets <<= 1;
  // Cell coordinates are clamped so that a far-flung (or exploded) particle
  // cannot overflow the integer conversion; such particles share edge cells.
  auto toCell = [&](double coordinate) {
    const double c = std::floor(coordinate / cell);
    return static_cast<int>(std::isfinite(c) ? std::clamp(c, -1e9, 1e9) : 1e9);
  };
  auto bucketOf = [&](const Eigen::Vector2i& c) {
    const unsigned long long h = static_cast<unsigned long long>(c.x()) * 73856093ULL ^
                                 static_cast<unsigned long long>(c.y()) * 19349663ULL;
    return static_cast<int>(h & static_cast<unsigned long long>(buckets - 1));
  };
  S.cells.resize(count);
  S.bucket.resize(count);
  S.bucketStart.assign(buckets + 1, 0);
  for (int a = 0; a < count; ++a) {
    const int i = collidable[a];
    S.cells[a] = Eigen::Vector2i(toCell(x[2 * i]), toCell(x[2 * i + 1]));
    S.bucket[a] = bucketOf(S.cells[a]);
    ++S.bucketStart[S.bucket[a] + 1];
  }
  for (int b = 0; b < buckets; ++b) S.bucketStart[b + 1] += S.bucketStart[b];
  S.order.resize(count);
  S.fill.assign(S.bucketStart.begin(), S.bucketStart.end() - 1);
  for (int a = 0; a < count; ++a) S.order[S.fill[S.bucket[a]]++] = a;
  for (int a = 0; a < count; ++a)
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy) {
        const Eigen::Vector2i c = S.cells[a] + Eigen::Vector2i(dx, dy);
        const int bucket = bucketOf(c);
        for (int s = S.bucketStart[bucket]; s < S.bucketStart[bucket + 1]; ++s) {
          const int b = S.order[s];
          if (b > a && S.cells[b] == c) S.pairs.emplace_back(a, b);  // each pair once; skip hash collisions
        }
      }
}

ContactCount ParticleContacts::resolveImpacts(const std::vector<int>& collidable,
                                              const std::vector<Collider>& colliders, const StepStart& start,
                                              const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                                              const ContactSettings& settings, Eigen::VectorXd& x,
                                              Eigen::VectorXd& v, Eigen::VectorXd* lastFree) {
  Scratch& S = *scratch_;
  // Event-driven over the step: every disc's next impact (against a collider
  // or another disc) is predicted on its track, and the earliest is applied
  // first, so each impact happens on the paths the discs really follow then.
  // An impact changes the tracks of its discs only; the predictions that
  // involve them are made again (older ones in the queue are recognised as
  // stale by the discs' stamps). Each disc takes at most maxImpacts impacts
  // (the work cap): one that would take more is counted in `capped`.
  const int count = static_cast<int>(collidable.size());
  const double dt = start.dt;
  const contact::ColliderBoxes boxes(colliders);
  S.tracks.resize(count);
  S.stamp.assign(count, 0);
  for (int a = 0; a < count; ++a) S.tracks[a] = contact::Track::of(start, collidable[a], x, v);
  // The candidate pairs of each disc, as offsets into S.pairs (compressed rows).
  S.pairsOfStart.assign(count + 1, 0);
  for (const auto& [a, b] : S.pairs) ++S.pairsOfStart[a + 1], ++S.pairsOfStart[b + 1];
  for (int a = 0; a < count; ++a) S.pairsOfStart[a + 1] += S.pairsOfStart[a];
  S.pairsOf.resize(S.pairsOfStart[count]);
  S.fill.assign(S.pairsOfStart.begin(), S.pairsOfStart.end() - 1);
  for (int p = 0; p < static_cast<int>(S.pairs.size()); ++p) {
    S.pairsOf[S.fill[S.pairs[p].first]++] = p;
    S.pairsOf[S.fill[S.pairs[p].second]++] = p;
  }

  S.queue.clear();
  auto later = [](const Scratch::Event& e, const Scratch::Event& f) { return e.tau > f.tau; };
  auto push = [&](const Scratch::Event& e) {
    S.queue.push_back(e);
    std::push_heap(S.queue.begin(), S.queue.end(), later);
  };
  auto movable = [&](int a) { return inverseMass[collidable[a]] > 0.0 && S.tracks[a].impacts < settings.maxImpacts; };
  auto predictWall = [&](int a) {
    if (colliders.empty() || !movable(a)) return;
    const std::optional<contact::ColliderImpact> hit =
        contact::nextColliderImpact(colliders, boxes, S.tracks[a], radius[collidable[a]], settings.slop, dt);
    if (hit) push({hit->tau, a, -1, S.stamp[a], 0, *hit, {}});
  };
  auto predictPair = [&](int p) {
    const auto [a, b] = S.pairs[p];
    if (inverseMass[collidable[a]] + inverseMass[collidable[b]] == 0.0) return;
    if (S.tracks[a].impacts >= settings.maxImpacts || S.tracks[b].impacts >= settings.maxImpacts) return;
    const std::optional<PairImpact> hit =
        nextPairImpact(S.tracks[a], S.tracks[b], radius[collidable[a]] + radius[collidable[b]],
                       settings.particleRestitution,
                       settings.slop, dt);
    if (hit) push({hit->tau, a, b, S.stamp[a], S.stamp[b], {}, *hit});
  };
  auto predictPairsOf = [&](int a) {
    for (int k = S.pairsOfStart[a]; k < S.pairsOfStart[a + 1]; ++k) predictPair(S.pairsOf[k]);
  };
  auto predictAll = [&](int a) {
    predictWall(a);
    predictPairsOf(a);
  };
  for (int a = 0; a < count; ++a) predictWall(a);
  for (int p = 0; p < static_cast<int>(S.pairs.size()); ++p) predictPair(p);

  ContactCount contacts;
  while (!S.queue.empty()) {
    std::pop_heap(S.queue.begin(), S.queue.end(), later);
    const Scratch::Event e = S.queue.back();
    S.queue.pop_back();
    if (e.stampA != S.stamp[e.a] || (e.b >= 0 && e.stampB != S.stamp[e.b])) continue;  // stale
    ++contacts.contacts;
    ++S.stamp[e.a];
    if (e.b < 0) {
      // A resting contact met again without effect settles the disc on that
      // surface: only its pairs are predicted again.
      if (contact::applyColliderImpact(colliders[e.wall.collider], e.wall, radius[collidable[e.a]], settings.slop, dt,
                                       S.tracks[e.a]))
        predictAll(e.a);
      else
        predictPairsOf(e.a);
    } else {
      ++S.stamp[e.b];
      applyPairImpact(e.pair, inverseMass[collidable[e.a]], inverseMass[collidable[e.b]], dt, S.tracks[e.a],
                      S.tracks[e.b]);
      predictAll(e.a);
      predictAll(e.b);
    }
  }

  for (int a = 0; a < count; ++a) {
    const int i = collidable[a];
    contact::Track& track = S.tracks[a];
    if (track.impacts >= settings.maxImpacts &&
        (colliders.empty() || contact::stopIfStillEntering(colliders, boxes, radius[i], settings.slop, track)))
      ++contacts.capped;
    x.segment<2>(2 * i) = track.x1;
    v.segment<2>(2 * i) = track.v1;
    if (lastFree) lastFree->segment<2>(2 * i) = track.x1;
  }
  return contacts;
}

double ParticleContacts::resolveResting(const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                                        const ContactSettings& settings, bool reverse, Eigen::VectorXd& x,
                                        Eigen::VectorXd& v) {
  double largest = 0.0;
  const int count = static_cast<int>(touching_.size());
  for (int k = 0; k < count; ++k) {
    const auto [i, j] = touching_[reverse ? count - 1 - k : k];
    largest = std::max(largest, restingPair(i, j, inverseMass, radius, settings, x, v));
  }
  return largest;
}

}  // namespace particles
