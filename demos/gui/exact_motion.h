#pragma once
// The exact motion of the scenes that have one, drawn as a ghost beside the
// simulation (key g): the oscillator's closed form, and the pendulum's
// large-angle motion from the inverse of the elliptic integral.
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "particles/particle_system.h"
#include "scene_keys.h"

namespace demo {

struct GhostFrame {
  std::vector<Eigen::Vector2d> points;                              // ghost particles
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> springs;  // drawn as coils
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> rods;     // drawn as lines
};
using ExactMotion = std::function<GhostFrame(double t)>;

// The exact motion of a built-in scene, or an empty function when it has none
// or when its state at t = 0 is not the built scene's `initial` one (so a ghost
// never shows a different problem than the one simulated).
ExactMotion exactMotion(const SceneChoice& choice, const particles::ParticleSystem& initial);

// Jacobi's sn(u, k) for 0 ≤ k < 1, by inverting u = F(φ, k) (scenes::ellipticF, scenes/elliptic.h) for
// the amplitude φ = am(u, k) on [0, π/2] and the quarter-period symmetries.
double jacobiSn(double u, double k);

}  // namespace demo
