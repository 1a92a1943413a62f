// Seeded fuzzing of the scene-file reader, in process so that it is fast and
// runs in the sanitizer build. Mutants of the shipped example files and of
// every exported built-in scene — byte flips, truncations, values swapped for
// another JSON type, huge, negative, tiny and NaN numbers, out-of-range
// particle indices, dropped fields — must each either be rejected with a
// one-line SceneFileError (the runner's exit 2) or load and step. A mutant
// that loads may be one no integrator can step (a stiffness of 1e300): it
// must then be caught as non-finite (the runner's exit 3), never crash, hang,
// throw anything else or trip a sanitizer.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "particles/integrator.h"
#include "scene.h"
#include "scene_file/scene_file.h"

namespace {

using scenes::Json;

enum class Outcome { Rejected, SteppedFinite, CaughtNonFinite };

Outcome loadAndStep(const std::string& text) {
  scenes::Scene scene;
  try {
    scene = scenes::readScene(text, "mutant");
  } catch (const scenes::SceneFileError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.rfind("mutant: $", 0), 0u) << message;
    return Outcome::Rejected;
  }
  auto integrator = particles::makeIntegrator(scene.integrator);
  for (int k = 0; k < 10; ++k) {
    scene.system->step(*integrator, scene.dt);
    if (!scene.system->finite()) return Outcome::CaughtNonFinite;
  }
  return Outcome::SteppedFinite;
}

std::vector<std::string> baseFiles() {
  std::vector<std::string> bases;
  for (const auto& entry : std::filesystem::directory_iterator(SCENES_DIR)) {
    if (entry.path().extension() != ".json") continue;
    std::ifstream in(entry.path());
    std::ostringstream text;
    text << in.rdbuf();
    bases.push_back(text.str());
  }
  for (const scenes::SceneInfo& info : scenes::sceneTable())
    bases.push_back(scenes::writeScene(scenes::buildScene(info.name)));
  return bases;
}

class Mutator {
 public:
  explicit Mutator(unsigned seed) : rng_(seed) {}

  std::string mutate(const std::string& base) {
    switch (pick(6)) {
      case 0: {  // flip one byte to any value
        std::string text = base;
        text[pick(text.size())] = static_cast<char>(pick(256));
        return text;
      }
      case 1:
        return base.substr(0, pick(base.size()));
      default:
        return mutateStructure(base);
    }
  }

 private:
  std::size_t pick(std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_); }

  // Changes one leaf of the parsed document (or drops it).
  std::string mutateStructure(const std::string& base) {
    Json doc = Json::parse(base);
    const Json flat = doc.flatten();
    std::vector<std::string> leaves, numbers, indices;
    for (const auto& item : flat.items()) {
      leaves.push_back(item.key());
      if (item.value().is_number()) numbers.push_back(item.key());
      if (item.value().is_number_integer() && item.key().find("particle") != std::string::npos)
        indices.push_back(item.key());
    }
    const int n = static_cast<int>(doc["particles"].size());
    const std::size_t kind = pick(4);
    if (kind == 0 || numbers.empty()) {  // a value of another JSON type
      static const Json others[] = {"text", true, nullptr, Json::object(), Json::array(), Json::array({1, 2, 3}), 7};
      doc[Json::json_pointer(leaves[pick(leaves.size())])] = others[pick(std::size(others))];
    } else if (kind == 1) {  // an extreme number; NaN and Infinity as the text a careless writer produces
      static const char* extremes[] = {"1e308", "-1e308", "1e300", "-1", "0", "-0.0", "1e-308", "5e-324",
                                       "1e18", "-2147483649", "4294967296", "NaN", "Infinity", "-1e999"};
      const std::string marker = "\"@extreme@\"";
      doc[Json::json_pointer(numbers[pick(numbers.size())])] = "@extreme@";
      std::string text = doc.dump();
      return text.replace(text.find(marker), marker.size(), extremes[pick(std::size(extremes))]);
    } else if (kind == 2 && !indices.empty()) {  // a particle index out of range
      const long long bad[] = {-1, n, n + 7, 2147483648LL, 1000000000000LL};
      doc[Json::json_pointer(indices[pick(indices.size())])] = bad[pick(std::size(bad))];
    } else {  // drop a field or element
      const Json::json_pointer leaf(leaves[pick(leaves.size())]);
      Json& parent = doc[leaf.parent_pointer()];
      if (parent.is_object()) parent.erase(leaf.back());
      else if (parent.is_array()) parent.erase(std::stoul(leaf.back()));
    }
    return doc.dump();
  }

  std::mt19937 rng_;
};

TEST(SceneFileFuzz, EveryMutantIsRejectedOrStepsOrIsCaughtNonFinite) {
  const std::vector<std::string> bases = baseFiles();
  ASSERT_GE(bases.size(), 16u);
  Mutator mutator(20261123);
  int counts[3] = {0, 0, 0};
  const int cases = 3000;
  for (int k = 0; k < cases; ++k) {
    const std::string mutant = mutator.mutate(bases[k % bases.size()]);
    counts[static_cast<int>(loadAndStep(mutant))]++;
    if (HasFailure()) {
      ADD_FAILURE() << "case " << k << ":\n" << mutant.substr(0, 2000);
      return;
    }
  }
  std::printf("[ fuzz     ] %d mutants: %d rejected, %d stepped finite, %d caught non-finite\n", cases,
              counts[0], counts[1], counts[2]);
  EXPECT_GT(counts[0], 0);
  EXPECT_GT(counts[1], 0);
}

}  // namespace
