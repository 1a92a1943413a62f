// Each force type is described once in each layer that chooses by type: the
// engine's fast paths (src/forces/force_kinds.cpp), the scene file's codecs
// (demos/scene_file/force_codecs.cpp) and the demo's colours
// (demos/gui/palette.h). The layers name the same types, and a force of
// another class that takes a built-in type's name keeps its own apply.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <set>
#include <string>

#include "forces/force_batch.h"
#include "forces/force_kinds.h"
#include "integrators/xpbd.h"
#include "palette.h"
#include "particles/forces/gravity.h"
#include "particles/forces/spring.h"
#include "particles/particle_system.h"
#include "scene_file/codecs.h"

namespace {

std::set<std::string> codecTypes() {
  std::set<std::string> types;
  for (const scenes::ForceCodec& codec : scenes::forceCodecs()) types.insert(codec.type);
  return types;
}

TEST(ForceTypes, EveryLayerNamesTheSameForceTypes) {
  const std::set<std::string> codecs = codecTypes();
  for (const particles::ForceKind& kind : particles::forceKinds()) {
    EXPECT_EQ(codecs.count(kind.type), 1u) << kind.type << ": a fast path but no codec";
    EXPECT_TRUE(kind.batch || kind.positionForm) << kind.type << ": a row with no entry";
  }
  std::set<std::string> constraints;
  for (const scenes::ConstraintCodec& codec : scenes::constraintCodecs()) constraints.insert(codec.type);
  std::set<std::string> coloured;
  for (const demo::TypeColours& row : demo::typeColours) {
    EXPECT_TRUE(coloured.insert(row.type).second) << row.type << ": two colour rows";
    EXPECT_TRUE(codecs.count(row.type) || constraints.count(row.type) || std::strcmp(row.type, "constraint") == 0)
        << row.type << ": colours for a type no scene file can hold";
  }
  for (const std::string& type : codecs) EXPECT_EQ(coloured.count(type), 1u) << type << ": no colour row";
  for (const std::string& type : constraints) EXPECT_EQ(coloured.count(type), 1u) << type << ": no colour row";
}

// A user's force that calls itself "spring" but is no SpringForce: 1 N to the
// right on particle 0.
class NamedLikeASpring : public particles::Force {
 public:
  const char* type() const override { return "spring"; }
  void apply(const particles::Phase&, Eigen::VectorXd& f) const override { f[0] += 1.0; }
};

TEST(ForceTypes, AForceNamedLikeABuiltInTypeKeepsItsOwnApply) {
  particles::ParticleSystem system;
  system.addParticle({0.0, 0.0}, 2.0);
  system.addParticle({1.0, 0.0}, 2.0);
  system.addForce(std::make_unique<particles::SpringForce>(0, 1, 1.0, 10.0, 0.0));
  const particles::Force& named = system.addForce(std::make_unique<NamedLikeASpring>());
  system.addForce(std::make_unique<particles::GravityForce>(Eigen::Vector2d(0.0, -9.81)));

  particles::ForceBatches batches;
  batches.update(system.forceObjects(), system.structureStamp());
  Eigen::VectorXd f = Eigen::VectorXd::Zero(4);
  batches.apply(system.phase(), f);
  EXPECT_DOUBLE_EQ(f[0], 1.0) << "its push, the spring at rest";
  EXPECT_DOUBLE_EQ(f[1], -2.0 * 9.81);
  EXPECT_DOUBLE_EQ(f[2], 0.0);
  EXPECT_EQ(batches.springCount(), 1);

  const auto forms = particles::XpbdIntegrator::positionForms(system, 1e-3);
  EXPECT_EQ(forms.distances.size(), 1u) << "the real spring only";
  ASSERT_EQ(forms.applied.size(), 2u);
  EXPECT_EQ(forms.applied[0], &named);
}

}  // namespace
