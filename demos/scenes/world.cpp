#include "scenes/world.h"

#include <memory>

#include "particles/forces/gravity.h"

namespace scenes {

void addGravity(particles::ParticleSystem& system, double g) {
  if (g != 0.0) system.addForce(std::make_unique<particles::GravityForce>(Eigen::Vector2d(0.0, -g)));
}

int addRodChain(particles::ParticleSystem& system, const Eigen::Vector2d& start,
                const Eigen::Vector2d& end, int links, double mass, particles::RodForm form) {
  std::vector<Eigen::Vector2d> positions;
  for (int k = 0; k <= links; ++k) positions.push_back(start + (end - start) * (double(k) / links));
  const int first = system.addParticles(positions, std::vector<double>(positions.size(), mass));
  const double length = (end - start).norm() / links;
  for (int k = 0; k < links; ++k)
    system.addConstraint(std::make_unique<particles::RodConstraint>(first + k, first + k + 1, length, form));
  return first;
}

}  // namespace scenes
