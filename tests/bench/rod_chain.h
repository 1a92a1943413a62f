#pragma once
// The rod chain bench_step times, also run by the tests that make claims
// about it (Dopri5.TheDefaultToleranceBeatsRk4AtTheScenesStep): one
// definition, so both see the same chain.
#include <memory>

#include <Eigen/Core>

#include "particles/constraints/rod.h"
#include "particles/forces/gravity.h"
#include "particles/particle_system.h"

namespace bench {

// `count` particles of mass 1 spaced `link` apart along +x from the origin,
// joined by squared-form rods, the first pinned; gravity −9.81 along y
// (released horizontally).
inline particles::ParticleSystem horizontalRodChain(int count, double link) {
  particles::ParticleSystem system;
  for (int i = 0; i < count; ++i) system.addParticle(Eigen::Vector2d(i * link, 0.0), 1.0);
  system.setPinned(0, true);
  for (int i = 0; i + 1 < count; ++i)
    system.addConstraint(std::make_unique<particles::RodConstraint>(i, i + 1, link, particles::RodForm::Squared));
  system.addForce(std::make_unique<particles::GravityForce>(Eigen::Vector2d(0.0, -9.81)));
  return system;
}

}  // namespace bench
