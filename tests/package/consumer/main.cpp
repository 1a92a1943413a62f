// One particle under gravity, one symplectic Euler step of h: v = g h,
// x = x0 + g h². Exits 0 only when the installed library computes exactly that.
#include <cmath>
#include <cstdio>
#include <memory>

#include <particles/forces/gravity.h>
#include <particles/integrator.h>
#include <particles/particle_system.h>

int main() {
  particles::ParticleSystem system;
  system.addParticle({0.0, 1.0}, 2.0);
  system.addForce(std::make_unique<particles::GravityForce>(Eigen::Vector2d(0.0, -9.81)));
  auto integrator = particles::makeIntegrator("symplectic-euler");
  const double h = 0.01;
  system.step(*integrator, h);
  const double y = system.position(0).y(), vy = system.velocity(0).y();
  const bool ok = std::abs(vy + 9.81 * h) < 1e-12 && std::abs(y - (1.0 - 9.81 * h * h)) < 1e-12;
  std::printf("y = %.12f, vy = %.12f: %s\n", y, vy, ok ? "ok" : "wrong");
  return ok ? 0 : 1;
}
