// Disc–disc contacts: a uniform-grid broad phase, impacts at the time of
// impact with restitution, resting pairs split by inverse mass.
#include <algorithm>
#include <cmath>

#include "contact_path.h"
#include "particles/check.h"
#include "particles/collision.h"

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

}  // namespace

int ParticleContacts::resolve(const std::vector<int>& collidable, const StepStart& start,
                              const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                              const ContactSettings& settings, bool impacts, Eigen::VectorXd& x,
                              Eigen::VectorXd& v, ContactEvents* events) {
  // A public field rather than a constructor argument, so it is checked where it is used.
  requireInRange("particle contact restitution", restitution, 0.0, 1.0);
  const int count = static_cast<int>(collidable.size());
  if (count < 2) return 0;
  const double dt = start.dt, settled = settings.slop / dt;  // speed that moves the slop in a step
  double maxRadius = 0.0, maxTravel = 0.0;
  for (int i : collidable) {
    maxRadius = std::max(maxRadius, radius[i]);
    if (impacts) maxTravel = std::max(maxTravel, (x.segment<2>(2 * i) - start.x.segment<2>(2 * i)).norm());
  }
  // Any pair that touches during the step lies in neighbouring cells at its end.
  const double cell = 2.0 * (maxRadius + maxTravel);
  if (!(cell > 0.0) || !std::isfinite(cell)) return 0;

  // Broad phase: hash each disc's cell into a table of 2·count buckets, and
  // sort particles by bucket (counting sort, linear time).
  int buckets = 1;
  while (buckets < 2 * count) buckets <<= 1;
  // Cell coordinates are clamped so that a far-flung (or exploded) particle
  // cannot overflow the integer conversion; such particles share edge cells.
  auto toCell = [&](double coordinate) {
    const double c = std::floor(coordinate / cell);
    return static_cast<int>(std::isfinite(c) ? std::clamp(c, -1e9, 1e9) : 1e9);
  };
  auto cellOf = [&](int i) { return Eigen::Vector2i(toCell(x[2 * i]), toCell(x[2 * i + 1])); };
  auto bucketOf = [&](const Eigen::Vector2i& c) {
    const unsigned long long h = static_cast<unsigned long long>(c.x()) * 73856093ULL ^
                                 static_cast<unsigned long long>(c.y()) * 19349663ULL;
    return static_cast<int>(h & static_cast<unsigned long long>(buckets - 1));
  };
  std::vector<Eigen::Vector2i>& cells = cells_;
  cells.resize(count);
  bucket_.resize(count);
  bucketStart_.assign(buckets + 1, 0);
  for (int a = 0; a < count; ++a) {
    cells[a] = cellOf(collidable[a]);
    bucket_[a] = bucketOf(cells[a]);
    ++bucketStart_[bucket_[a] + 1];
  }
  for (int b = 0; b < buckets; ++b) bucketStart_[b + 1] += bucketStart_[b];
  order_.resize(count);
  fill_.assign(bucketStart_.begin(), bucketStart_.end() - 1);
  for (int a = 0; a < count; ++a) order_[fill_[bucket_[a]]++] = a;

  auto pairContact = [&](int i, int j) {
    const double wi = inverseMass[i], wj = inverseMass[j], wsum = wi + wj;
    if (wsum == 0.0) return false;
    const double reach = radius[i] + radius[j];
    const Eigen::Vector2d d1 = x.segment<2>(2 * i) - x.segment<2>(2 * j);
    if (impacts) {
      // Each disc's path as it ends the step holds since its last event (an
      // impact earlier in the step bent the path before it); both hold from
      // the later of the two, t0.
      const contact::Path pi = contact::Path::of(start, i, x, v), pj = contact::Path::of(start, j, x, v);
      const double t0 = events ? std::max(events->t[i], events->t[j]) : 0.0, span = dt - t0;
      const Eigen::Vector2d d0 = pi.position(t0) - pj.position(t0);
      // Apart at t0: the relative chord d0 → d1 (exact when both accelerate
      // alike, as in a uniform field) meets |d| = reach at s, the time of
      // impact t0 + s·(dt − t0). Touching or overlapping at t0 (a third disc
      // pushed one into the other): s = 0.
      std::optional<double> s = 0.0;
      if (d0.norm() - reach > settings.slop) s = contact::enterCircle(d0, d1 - d0, Eigen::Vector2d::Zero(), reach);
      if (!s) return false;
      const double tau = t0 + *s * span, remaining = dt - tau;
      const Eigen::Vector2d dTau = d0 + *s * (d1 - d0);
      const Eigen::Vector2d n = dTau.norm() > 0.0 ? Eigen::Vector2d(dTau.normalized()) : Eigen::Vector2d(1, 0);
      const double un = (pi.velocity(tau) - pj.velocity(tau)).dot(n);
      const contact::NormalChange change = contact::normalChange(un, (pi.a - pj.a).dot(n), remaining, restitution);
      // Touching at the start, an approach slower than the accelerations bring
      // in a step is a resting contact pressed on (a stack), not an impact.
      const double resting = *s > 0.0 ? settled : std::max(settled, (pi.a.norm() + pj.a.norm()) * dt);
      if (un < -resting && !change.resting) {
        // Equal and opposite impulses P at τ, displacing each end by Δv (dt − τ).
        const double impulse = change.dv / wsum;
        const Eigen::Vector2d dvi = impulse * wi * n, dvj = -impulse * wj * n;
        v.segment<2>(2 * i) += dvi;
        v.segment<2>(2 * j) += dvj;
        if (events) {
          events->x.segment<2>(2 * i) = pi.position(tau);
          events->x.segment<2>(2 * j) = pj.position(tau);
          events->t[i] = events->t[j] = tau;
        }
        x.segment<2>(2 * i) += remaining * dvi;
        x.segment<2>(2 * j) += remaining * dvj;
        touching_.emplace_back(i, j);  // a later push may close them again
        return true;
      }
    }
    if (d1.squaredNorm() >= (reach + settings.slop) * (reach + settings.slop)) return false;
    touching_.emplace_back(i, j);
    return restingPair(i, j, inverseMass, radius, settings, x, v) >= 0.0;
  };
  touching_.clear();

  int contacts = 0;
  for (int a = 0; a < count; ++a) {
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy) {
        const Eigen::Vector2i c = cells[a] + Eigen::Vector2i(dx, dy);
        const int bucket = bucketOf(c);
        for (int s = bucketStart_[bucket]; s < bucketStart_[bucket + 1]; ++s) {
          const int b = order_[s];
          if (b <= a || cells[b] != c) continue;  // each pair once; skip hash collisions
          if (pairContact(collidable[a], collidable[b])) ++contacts;
        }
      }
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
