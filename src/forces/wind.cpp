#include "particles/forces/wind.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "particles/check.h"
#include "particles/constants.h"

namespace particles {

void WindSettings::validate() const {
  requireNonNegative("wind speed", speed);
  requireFinite("wind direction", direction);
  requireNonNegative("wind drag", drag);
  requireInRange("wind gust", gust, 0.0, 1.0);
  requirePositive("wind gust period", gustPeriod);
  if (seed < 0) throw std::invalid_argument("wind seed must be >= 0, got " + std::to_string(seed));
}

namespace {

// SplitMix64 (Steele, Lea & Flood 2014): a well-mixed 64-bit value per input,
// here the gust phases' source, the same on every platform.
std::uint64_t splitMix64(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

constexpr double kGustPeriodRatio[3] = {1.0, 1.0 / 2.13, 1.0 / 4.37};
constexpr double kGustAmplitude[3] = {1.0, 0.6, 0.35};

// a = R d: d turned by +90°.
Eigen::Vector2d turned(const Eigen::Vector2d& d) { return {-d.y(), d.x()}; }
Eigen::Matrix2d rotation() {
  Eigen::Matrix2d R;
  R << 0.0, -1.0, 1.0, 0.0;
  return R;
}

}  // namespace

double gustShape(double time, double period, int seed) {
  double sum = 0.0, total = 0.0;
  for (int k = 0; k < 3; ++k) {
    const std::uint64_t bits = splitMix64(3 * static_cast<std::uint64_t>(seed) + k);
    const double phase = 2.0 * kPi * static_cast<double>(bits >> 11) * 0x1.0p-53;
    sum += kGustAmplitude[k] * std::sin(2.0 * kPi * time / (period * kGustPeriodRatio[k]) + phase);
    total += kGustAmplitude[k];
  }
  return sum / total;
}

Eigen::Vector2d airVelocity(const WindSettings& wind, double time) {
  const double speed =
      wind.gust > 0.0 ? wind.speed * (1.0 + wind.gust * gustShape(time, wind.gustPeriod, wind.seed)) : wind.speed;
  return speed * Eigen::Vector2d(std::cos(wind.direction), std::sin(wind.direction));
}

Eigen::Vector2d windEdgeForce(const Eigen::Vector2d& d, const Eigen::Vector2d& u, double drag) {
  const double lengthSquared = d.squaredNorm();
  if (lengthSquared == 0.0) return Eigen::Vector2d::Zero();
  const Eigen::Vector2d a = turned(d);
  const double p = u.dot(a);
  return (drag * std::abs(p) * p / lengthSquared) * a;
}

void windEdgeJacobian(const Eigen::Vector2d& d, const Eigen::Vector2d& u, double drag, Eigen::Matrix2d& dFdd,
                      Eigen::Matrix2d& dFdu) {
  const double lengthSquared = d.squaredNorm();
  if (lengthSquared == 0.0) {
    dFdd.setZero();
    dFdu.setZero();
    return;
  }
  const Eigen::Vector2d a = turned(d);
  const double p = u.dot(a), magnitude = std::abs(p);
  dFdu = (2.0 * drag * magnitude / lengthSquared) * a * a.transpose();
  const Eigen::Matrix2d dFda = (drag / lengthSquared) * (2.0 * magnitude * a * u.transpose() +
                                                         magnitude * p * Eigen::Matrix2d::Identity() -
                                                         (2.0 * magnitude * p / lengthSquared) * a * a.transpose());
  dFdd = dFda * rotation();
}

WindForce::WindForce(std::vector<std::array<int, 2>> edges, const WindSettings& settings)
    : edges_(std::move(edges)), settings_(settings) {
  settings_.validate();
  for (const auto& [i, j] : edges_)
    if (i == j) throw std::invalid_argument("wind edge joins particle " + std::to_string(i) + " to itself");
  air_ = airVelocity(settings_, time_);
}

std::vector<int> WindForce::particles() const {
  std::vector<int> ends;
  ends.reserve(2 * edges_.size());
  for (const auto& [i, j] : edges_) {
    ends.push_back(i);
    ends.push_back(j);
  }
  return ends;
}

void WindForce::setTime(double time) {
  time_ = time;
  air_ = airVelocity(settings_, time_);
}

bool WindForce::dropLinks(const LinkSet& broken) {
  const std::size_t before = edges_.size();
  edges_.erase(std::remove_if(edges_.begin(), edges_.end(),
                              [&](const std::array<int, 2>& e) { return broken.contains(e[0], e[1]); }),
               edges_.end());
  return edges_.size() != before;
}

void WindForce::setSettings(const WindSettings& settings) {
  settings.validate();
  settings_ = settings;
  air_ = airVelocity(settings_, time_);
}

Eigen::Vector2d WindForce::relativeAir(const Phase& s, int i, int j) const {
  return air_ - 0.5 * (s.velocity(i) + s.velocity(j));
}

void WindForce::apply(const Phase& s, Eigen::VectorXd& f) const {
  for (const auto& [i, j] : edges_) {
    const Eigen::Vector2d half =
        0.5 * windEdgeForce(s.position(j) - s.position(i), relativeAir(s, i, j), settings_.drag);
    f.segment<2>(2 * i) += half;
    f.segment<2>(2 * j) += half;
  }
}

namespace {
// The same 2×2 block B on (i, i), (i, j), (j, i), (j, j), with signs sign[row] · sign[col].
void addBlocks(Triplets& out, int i, int j, const Eigen::Matrix2d& B, const double rowSign[2], const double colSign[2]) {
  const int index[2] = {i, j};
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) out.emplace_back(2 * index[a] + r, 2 * index[b] + c, rowSign[a] * colSign[b] * B(r, c));
}
}  // namespace

// f_i = f_j = F/2 with d = x_j − x_i and u = w − ½(v_i + v_j):
//   ∂f_k/∂x_j = ½ ∂F/∂d,  ∂f_k/∂x_i = −½ ∂F/∂d,  ∂f_k/∂v_i = ∂f_k/∂v_j = −¼ ∂F/∂u.
void WindForce::addJacobians(const Phase& s, Triplets& dfdx, Triplets& dfdv) const {
  const double same[2] = {1.0, 1.0}, positions[2] = {-1.0, 1.0};
  Eigen::Matrix2d dFdd, dFdu;
  for (const auto& [i, j] : edges_) {
    windEdgeJacobian(s.position(j) - s.position(i), relativeAir(s, i, j), settings_.drag, dFdd, dFdu);
    addBlocks(dfdx, i, j, 0.5 * dFdd, same, positions);
    addBlocks(dfdv, i, j, -0.25 * dFdu, same, same);
  }
}

void WindForce::addDefiniteJacobians(const Phase& s, Triplets&, Triplets& dfdv) const {
  const double same[2] = {1.0, 1.0};
  Eigen::Matrix2d dFdd, dFdu;
  for (const auto& [i, j] : edges_) {
    windEdgeJacobian(s.position(j) - s.position(i), relativeAir(s, i, j), settings_.drag, dFdd, dFdu);
    addBlocks(dfdv, i, j, -0.25 * dFdu, same, same);
  }
}

}  // namespace particles
