#pragma once
// The mass-spring oscillator of every order and energy test: the oscillator
// scene (scenes/oscillator.h), a mass on a spring to a pinned anchor released
// at rest from `stretch` beyond the rest length, whose displacement has a
// closed form; and the measured order of a scheme's global error on it.
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "particles/constants.h"
#include "particles/integrator.h"
#include "particles/particle_system.h"
#include "scenes/oscillator.h"
#include "test_support.h"

namespace test_support {

// Global errors at time T of runs of `steps` equal steps each, and the order
// fitted to them.
struct OrderFit {
  std::vector<double> dts, errors;
  double order = 0.0;
};

struct Oscillator {
  // Unit mass, undamped, ω = 2π (a period of 1 s), swinging ±0.1 about a
  // rest length of 1; a test sets the fields it needs.
  scenes::OscillatorParams params = [] {
    scenes::OscillatorParams p;
    p.mass = 1.0;
    p.stiffness = 4.0 * particles::kPi * particles::kPi;
    p.damping = 0.0;
    p.rest = 1.0;
    p.stretch = 0.1;
    return p;
  }();

  static constexpr int kBob = 1;  // the scene adds the pinned anchor first

  double omega() const { return std::sqrt(params.stiffness / params.mass); }

  particles::ParticleSystem build() const {
    params.validate();
    scenes::Scene scene = scenes::buildOscillator(params);
    return std::move(*scene.system);
  }

  // The bob's position at time t: on the x axis, rest + u(t) from the anchor.
  Eigen::Vector2d exactPosition(double t) const {
    return Eigen::Vector2d(params.rest + scenes::oscillatorDisplacement(params, t), 0.0);
  }

  // The bob's distance from the closed form at the system's time.
  double error(const particles::ParticleSystem& system) const {
    return (system.position(kBob) - exactPosition(system.time())).norm();
  }

  // The scheme (made by name with `settings`) run to T in each of `steps`
  // equal steps: the log-log slope of the error at T against dt.
  OrderFit measureOrder(const std::string& scheme, double T, const std::vector<int>& steps,
                        const particles::IntegratorSettings& settings = {}) const {
    OrderFit fit;
    for (int n : steps) {
      particles::ParticleSystem system = build();
      auto integrator = particles::makeIntegrator(scheme, settings);
      const double dt = T / n;
      for (int k = 0; k < n; ++k) system.step(*integrator, dt);
      EXPECT_NEAR(system.time(), T, 1e-9) << scheme << " in " << n << " steps";
      fit.dts.push_back(dt);
      fit.errors.push_back(error(system));
    }
    fit.order = logLogSlope(fit.dts, fit.errors);
    return fit;
  }
};

}  // namespace test_support
