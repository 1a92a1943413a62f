// JSON scene files: every built-in scene survives export and reload bit for
// bit, and every shipped example loads and steps.
#include <gtest/gtest.h>

#include <filesystem>

#include "particles/integrator.h"
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

TEST(SceneFile, ParametersSurviveExport) {
  scenes::Scene cloth = scenes::buildScene("cloth", {{"width", "5"}, {"height", "4"}, {"links", "8"}});
  const scenes::Scene loaded = scenes::readScene(scenes::writeScene(cloth), "cloth");
  EXPECT_EQ(loaded.system->size(), 20);
  // Rows of 4 horizontal springs ×4, columns of 3 vertical ×5, 2 diagonals
  // in each of the 4·3 cells, gravity and air drag.
  EXPECT_EQ(loaded.system->forceObjects().size(), 16u + 15u + 24u + 1u + 1u);
  EXPECT_EQ(loaded.system->constraints().size(), 5u);
  EXPECT_EQ(loaded.system->colliders().size(), 2u);
}

TEST(SceneFile, EveryShippedExampleLoadsAndSteps) {
  int examples = 0;
  for (const auto& entry : std::filesystem::directory_iterator(SCENES_DIR)) {
    if (entry.path().extension() != ".json") continue;
    ++examples;
    scenes::Scene scene = scenes::loadSceneFile(entry.path().string());
    auto integrator = particles::makeIntegrator(scene.integrator);
    for (int k = 0; k < 200; ++k) scene.system->step(*integrator, scene.dt);
    EXPECT_TRUE(scene.system->finite()) << entry.path();
    EXPECT_LE(scene.system->maxRelativeConstraintError(), 0.01) << entry.path();
  }
  EXPECT_GE(examples, 8);  // one per force and constraint type
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
