#include "exact_motion.h"

#include <algorithm>
#include <cmath>

#include "particles/constants.h"
#include "scenes/elliptic.h"
#include "scenes/oscillator.h"
#include "scenes/param_fields.h"
#include "scenes/pendulum.h"

namespace demo {

double jacobiSn(double u, double k) {
  const double K = scenes::ellipticK(k);
  // sn has period 4K, is odd about 2K and symmetric about K.
  u = std::fmod(u, 4.0 * K);
  if (u < 0.0) u += 4.0 * K;
  double sign = 1.0;
  if (u >= 2.0 * K) {
    u -= 2.0 * K;
    sign = -1.0;
  }
  if (u > K) u = 2.0 * K - u;
  // F(φ, k) increases from 0 to K on [0, π/2]: bisection to the last bit.
  double lo = 0.0, hi = 0.5 * particles::kPi;
  for (int i = 0; i < 64 && hi - lo > 1e-16; ++i) {
    const double mid = 0.5 * (lo + hi);
    (scenes::ellipticF(k, mid) < u ? lo : hi) = mid;
  }
  return sign * std::sin(0.5 * (lo + hi));
}

namespace {
template <class Params>
Params paramsOf(const SceneChoice& choice) {
  const scenes::SceneInfo* info = scenes::findScene(choice.name);
  return info ? scenes::readParams<Params>(scenes::SceneParams(info->params, choice.params, choice.preset)) : Params{};
}

// The oscillator's ghost runs on a parallel track below the real one.
ExactMotion oscillator(const SceneChoice& choice) {
  const scenes::OscillatorParams p = paramsOf<scenes::OscillatorParams>(choice);
  const Eigen::Vector2d offset(0.0, -0.5 * p.rest);
  return [p, offset](double t) {
    GhostFrame g;
    const Eigen::Vector2d anchor = offset, bob = offset + Eigen::Vector2d(p.rest + scenes::oscillatorDisplacement(p, t), 0.0);
    g.points = {anchor, bob};
    g.springs.push_back({anchor, bob});
    return g;
  };
}

// The bead on its wire of radius L released at rest from θ₀: with
// k = sin(θ₀/2), ω₀ = √(g/L) and K = K(k),
//   sin(θ/2) = k sn(K − ω₀ t, k),
// the exact large-angle motion (θ = θ₀ at t = 0, period 4K/ω₀). The ghost
// hangs from the same pivot, so any phase error shows as the two apart.
ExactMotion pendulum(const SceneChoice& choice) {
  const scenes::PendulumParams p = paramsOf<scenes::PendulumParams>(choice);
  return [p](double t) {
    const double theta0 = p.angle * particles::kPi / 180.0, k = std::sin(0.5 * std::abs(theta0));
    const double omega0 = std::sqrt(p.gravity / p.length);
    const double s = k * jacobiSn(scenes::ellipticK(k) - omega0 * t, k);
    // θ swings through zero to −θ₀: its sign is sn's, mirrored for a release at a negative angle.
    const double theta = (theta0 < 0.0 ? -1.0 : 1.0) * 2.0 * std::asin(std::clamp(s, -1.0, 1.0));
    GhostFrame g;
    const Eigen::Vector2d centre(0.0, 0.0), bead = centre + p.length * Eigen::Vector2d(std::sin(theta), -std::cos(theta));
    g.points = {bead};
    g.rods.push_back({centre, bead});
    return g;
  };
}
}  // namespace

ExactMotion exactMotion(const SceneChoice& choice, const particles::ParticleSystem& initial) {
  ExactMotion motion;
  if (!choice.file.empty()) return motion;
  if (choice.name == "oscillator") motion = oscillator(choice);
  else if (choice.name == "pendulum") motion = pendulum(choice);
  if (!motion) return motion;
  // The ghost at t = 0 must sit where the scene starts (the oscillator's
  // ghost beside it by its offset): else it describes another problem.
  const GhostFrame start = motion(0.0);
  const int n = initial.size();
  if (static_cast<int>(start.points.size()) != n) return {};
  const Eigen::Vector2d shift = start.points.front() - initial.position(0);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d d = start.points[i] - initial.position(i) - (choice.name == "oscillator" ? shift : Eigen::Vector2d::Zero().eval());
    if (!(d.norm() <= 1e-9 * (1.0 + initial.position(i).norm()))) return {};
  }
  return motion;
}

}  // namespace demo
