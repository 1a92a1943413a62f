// JSON scene files: every built-in scene survives export and reload bit for
// bit, and every shipped example loads and steps.
#include <gtest/gtest.h>

#include <filesystem>

#include "particles/integrator.h"
#include "particles/particle_system.h"
#include "particles/solver_names.h"
#include "scene.h"
#include "scene_file/codecs.h"
#include "scene_file/scene_file.h"

namespace {

TEST(SceneFile, EveryBuiltInSceneRoundTripsBitForBitOver100Steps) {
  for (const scenes::SceneInfo& info : scenes::sceneTable()) {
    scenes::Scene original = scenes::buildScene(info.name);
    const std::string text = scenes::writeScene(original);
    scenes::Scene loaded = scenes::readScene(text, info.name);
    EXPECT_EQ(scenes::writeScene(loaded), text) << info.name;
    ASSERT_EQ(loaded.integrator, original.integrator);
    ASSERT_EQ(loaded.dt, original.dt);
    auto a = particles::makeIntegrator(original.integrator), b = particles::makeIntegrator(loaded.integrator);
    for (int k = 0; k < 100; ++k) {
      original.system->step(*a, original.dt);
      loaded.system->step(*b, loaded.dt);
      // Exact equality: the same operations on the same doubles.
      ASSERT_TRUE(original.system->positions() == loaded.system->positions()) << info.name << " step " << k;
      ASSERT_TRUE(original.system->velocities() == loaded.system->velocities()) << info.name << " step " << k;
    }
  }
}

// Every solver setting survives export → read, for every method and
// preconditioner; a file that asks for CG is solved by CG.
// xpbd's hanging lines are written and read back; absent, they are off.
TEST(SceneFile, XpbdLinesRoundTrip) {
  scenes::Scene cloth = scenes::buildScene("cloth");
  EXPECT_FALSE(scenes::readScene(scenes::writeScene(cloth), "cloth").integratorSettings.xpbd.lines);
  cloth.integratorSettings.xpbd.lines = true;
  const scenes::Scene loaded = scenes::readScene(scenes::writeScene(cloth), "cloth");
  EXPECT_TRUE(loaded.integratorSettings.xpbd.lines);
  EXPECT_FALSE(scenes::readScene(R"({"particles": [{"position": [0, 1], "mass": 1}]})", "bare")
                   .integratorSettings.xpbd.lines);
}

TEST(SceneFile, EverySolverSettingRoundTripsAndMethodCgSolvesByCg) {
  for (const auto& method : particles::solveMethodNames())
    for (const auto& preconditioner : particles::preconditionerNames()) {
      scenes::Scene chain = scenes::buildScene("test-chain");
      particles::SolverSettings& settings = chain.system->solver().settings;
      settings.method = method.value;
      settings.preconditioner = preconditioner.value;
      settings.tolerance = 1e-9;
      settings.maxIterations = 77;
      settings.maxCgWork = 12345.0;
      settings.stiffness = 12.5;
      settings.damping = 3.25;
      settings.warmStart = false;
      const std::string text = scenes::writeScene(chain);
      const scenes::Scene loaded = scenes::readScene(text, "solver-settings");
      const particles::SolverSettings& read = loaded.system->solver().settings;
      EXPECT_EQ(read.method, settings.method) << method.name;
      EXPECT_EQ(read.preconditioner, settings.preconditioner) << preconditioner.name;
      EXPECT_EQ(read.tolerance, settings.tolerance);
      EXPECT_EQ(read.maxIterations, settings.maxIterations);
      EXPECT_EQ(read.maxCgWork, settings.maxCgWork);
      EXPECT_EQ(read.stiffness, settings.stiffness);
      EXPECT_EQ(read.damping, settings.damping);
      EXPECT_EQ(read.warmStart, settings.warmStart);
      EXPECT_EQ(scenes::writeScene(loaded), text);
    }
  scenes::Scene cg = scenes::readScene(R"({"solver": {"method": "cg", "preconditioner": "incomplete-cholesky"},
      "particles": [{"position": [0, 0], "mass": 1, "pinned": true}, {"position": [0.5, 0], "mass": 1},
                    {"position": [1, 0], "mass": 1}],
      "forces": [{"type": "gravity", "acceleration": [0, -9.81]}],
      "constraints": [{"type": "rod", "particles": [0, 1], "length": 0.5},
                      {"type": "rod", "particles": [1, 2], "length": 0.5}]})",
                                       "cg");
  ASSERT_EQ(cg.system->solver().settings.method, particles::SolveMethod::ConjugateGradient);
  auto rk4 = particles::makeIntegrator("rk4");
  EXPECT_GT(cg.system->step(*rk4, 0.01).cgIterations, 0);
  try {
    scenes::readScene(R"({"solver": {"method": "lu"}})", "bad-method");
    ADD_FAILURE() << "an unknown method was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("\"direct\" or \"cg\""), std::string::npos) << e.what();
  }
}

TEST(SceneFile, ParametersSurviveExport) {
  scenes::Scene cloth = scenes::buildScene("cloth", {{"width", "5"}, {"height", "4"}, {"links", "8"}});
  const scenes::Scene loaded = scenes::readScene(scenes::writeScene(cloth), "cloth");
  EXPECT_EQ(loaded.system->size(), 20);
  // Rows of 4 horizontal springs ×4, columns of 3 vertical ×5, 2 diagonals
  // in each of the 4·3 cells, the faces' area floor, gravity and air drag.
  EXPECT_EQ(loaded.system->forceObjects().size(), 16u + 15u + 24u + 1u + 1u + 1u);
  EXPECT_EQ(loaded.system->constraints().size(), 5u);
  EXPECT_EQ(loaded.system->colliders().size(), 4u);  // the wall, the nail, the rail's end stops
  // The area floor's faces are the scene's surface again: shaded, blown on, torn.
  EXPECT_EQ(loaded.faces, cloth.faces);
  EXPECT_EQ(loaded.windEdges, cloth.windEdges);
  EXPECT_TRUE(loaded.edgeContacts);
}

TEST(SceneFile, EveryShippedExampleLoadsAndSteps) {
  int examples = 0;
  for (const auto& entry : std::filesystem::directory_iterator(SCENES_DIR)) {
    if (entry.path().extension() != ".json") continue;
    ++examples;
    scenes::Scene scene = scenes::loadSceneFile(entry.path().string());
    auto integrator = particles::makeIntegrator(scene.integrator);
    // 300 steps: polygon.json's block slides over the wedge's lower vertex at
    // step 134, where the chord of its resting track lies on the face.
    for (int k = 0; k < 300; ++k)
      EXPECT_EQ(scene.system->step(*integrator, scene.dt).failure, particles::StepFailure::None)
          << entry.path() << " step " << k + 1;
    EXPECT_TRUE(scene.system->finite()) << entry.path();
    EXPECT_LE(scene.system->maxRelativeConstraintError(), 0.01) << entry.path();
  }
  EXPECT_GE(examples, 8);  // one per force and constraint type
}

// The ball on the 10° slope of half-plane.json under dopri5 keeps bouncing:
// every contact restarts the adaptive scheme, and the restarted step must not
// inherit a step grown without bound in free flight (it froze from step 1535,
// its energy fallen from 9.81 J to −3.8 J). Over 30 s it moves in every 100
// steps and its energy stays within 1%.
TEST(SceneFile, HalfPlaneBallAdvancesUnderDopri5) {
  scenes::Scene scene = scenes::loadSceneFile(std::string(SCENES_DIR) + "/half-plane.json");
  auto dopri5 = particles::makeIntegrator("dopri5");
  const double e0 = scene.system->totalEnergy();
  Eigen::Vector2d last = scene.system->position(0);
  double smallestMove = 1e300, worstEnergy = 0.0;
  for (int k = 1; k <= 3000; ++k) {
    scene.system->step(*dopri5, scene.dt);
    worstEnergy = std::max(worstEnergy, std::abs(scene.system->totalEnergy() - e0) / std::abs(e0));
    if (k % 100 == 0) {
      smallestMove = std::min(smallestMove, (scene.system->position(0) - last).norm());
      last = scene.system->position(0);
    }
  }
  EXPECT_GT(smallestMove, 0.1) << "smallest distance moved in 100 steps: " << smallestMove << " m";
  EXPECT_LT(worstEnergy, 0.01) << "relative energy error " << worstEnergy;
}

TEST(SceneFile, ErrorsNameTheSourceThePathAndWhatWasExpected) {
  try {
    scenes::readScene(R"({"particles": [{"position": [0, 0], "mass": 1}, {"position": [1, 0], "mass": 0}]})",
                      "two.json");
    FAIL() << "a zero mass was accepted";
  } catch (const scenes::SceneFileError& e) {
    EXPECT_STREQ(e.what(), "two.json: $.particles[1].mass: expected a number > 0, got 0");
  }
}

// Values the engine refuses are reported, like a malformed one, at the
// field's path: a substep count of 0 (stored by JSON as unsigned), a tolerance
// below rounding, a zero half-plane normal shown as written.
TEST(SceneFile, RefusedSettingsNameTheFieldsPath) {
  const std::string particles = R"("particles": [{"position": [0, 1], "mass": 1}])";
  auto messageFor = [&](const std::string& member) {
    try {
      scenes::readScene("{" + particles + ", " + member + "}", "settings.json");
    } catch (const scenes::SceneFileError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(messageFor(R"("integratorSettings": {"substeps": 0})"),
            "settings.json: $.integratorSettings.substeps: expected an integer in [1, 100000], got 0");
  EXPECT_EQ(messageFor(R"("integratorSettings": {"lines": 1})"),
            "settings.json: $.integratorSettings.lines: expected true or false, got 1");
  EXPECT_EQ(messageFor(R"("integratorSettings": {"tolerance": 9.9e-14})"),
            "settings.json: $.integratorSettings.tolerance: integrator tolerance must be >= 1e-13 (below it double "
            "precision cannot meet it), got 9.9e-14");
  EXPECT_EQ(messageFor(R"("colliders": [{"type": "halfPlane", "point": [0, 0], "normal": [0, 0]}])"),
            "settings.json: $.colliders[0].normal: expected a non-zero vector, got [0,0]");
  EXPECT_EQ(messageFor(R"("colliders": [{"type": "halfPlane", "point": [0, 0], "normal": [1e308, 1e308]}])"),
            "accepted");
}

// The list of valid types in the message comes from the codec tables, so a
// new force or constraint type is named there without editing any test.
TEST(SceneFile, UnknownTypesAreRejectedListingEveryTypeOfTheTables) {
  const std::string particles = R"("particles": [{"position": [0, 0], "mass": 1}, {"position": [1, 0], "mass": 1}])";
  auto messageFor = [&](const std::string& list) {
    try {
      scenes::readScene("{" + particles + ", \"" + list + "\": [{\"type\": \"sprung\", \"particles\": [0, 1]}]}",
                        "types.json");
    } catch (const scenes::SceneFileError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string forces = messageFor("forces");
  for (const scenes::ForceCodec& codec : scenes::forceCodecs()) EXPECT_NE(forces.find(codec.type), std::string::npos) << forces;
  EXPECT_NE(forces.find("\"sprung\""), std::string::npos) << forces;
  const std::string constraints = messageFor("constraints");
  for (const scenes::ConstraintCodec& codec : scenes::constraintCodecs())
    EXPECT_NE(constraints.find(codec.type), std::string::npos) << constraints;
}

}  // namespace
