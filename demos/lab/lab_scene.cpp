#include "lab/lab_scene.h"

#include <cmath>
#include <random>

#include "particles/constants.h"

namespace lab {

scenes::Scene buildLabScene(const std::string& name, const std::map<std::string, std::string>& overrides) {
  return scenes::buildScene(name, overrides, scenes::kSeedPreset);
}

void perturbStart(scenes::Scene& scene, int member, double relativeSize) {
  if (member == 0) return;
  particles::ParticleSystem& system = *scene.system;
  const int n = system.size();
  if (n == 0) return;
  Eigen::Vector2d lo = system.position(0), hi = lo;
  for (int i = 0; i < n; ++i) lo = lo.cwiseMin(system.position(i)), hi = hi.cwiseMax(system.position(i));
  const double size = relativeSize * (hi - lo).norm();
  std::mt19937_64 random(0x9e3779b97f4a7c15ULL * static_cast<unsigned long long>(member));
  std::uniform_real_distribution<double> angle(0.0, 2.0 * particles::kPi);
  for (int i = 0; i < n; ++i) {
    const double a = angle(random);
    if (!system.pinned(i)) system.setPosition(i, system.position(i) + size * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
}

}  // namespace lab
