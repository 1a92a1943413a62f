// Seeded fuzzing of the scene-file reader, in process so that it is fast and
// runs in the sanitizer build. Mutants of the shipped example files and of
// every exported built-in scene — byte flips, truncations, values swapped for
// another JSON type, huge, negative, tiny and NaN numbers, out-of-range
// particle indices, dropped fields — must each either be rejected with a
// one-line SceneFileError (the runner's exit 2) or load and step. A mutant
// that loads may be one no integrator can step (a stiffness of 1e300): it
// must then be caught as non-finite (the runner's exit 3), never crash, hang,
// throw anything else or trip a sanitizer.
//
// Further generators aim at the reader's limits (demos/scene_limits.h):
// nesting thousands of levels deep, objects with up to 100,000 keys and
// duplicate keys, sizes beyond the limits in files and in the built-in scenes'
// parameters, and paths that are not regular files (devices, FIFOs,
// directories, oversize files).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>

#include <sys/stat.h>
#include <unistd.h>
#include <fstream>
#include <random>
#include <sstream>

#include "particles/integrator.h"
#include "scene.h"
#include "scene_file/scene_file.h"
#include "scene_limits.h"

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

// Under ASan+UBSan (CI's second run) each case costs about ten times as much:
// the fuzz tests take the first third of their cases there (1,000 mutants,
// every nesting depth twice); the Release run takes them all.
#if defined(__SANITIZE_ADDRESS__)
constexpr int kCaseDivisor = 3;
#else
constexpr int kCaseDivisor = 1;
#endif

TEST(SceneFileFuzz, EveryMutantIsRejectedOrStepsOrIsCaughtNonFinite) {
  const std::vector<std::string> bases = baseFiles();
  ASSERT_GE(bases.size(), 16u);
  Mutator mutator(20261123);
  int counts[3] = {0, 0, 0};
  const int cases = 3000 / kCaseDivisor;
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

// The message of a rejected text, checked to be one line naming the source and a JSON path.
std::string rejection(const std::string& text) {
  try {
    scenes::readScene(text, "mutant");
  } catch (const scenes::SceneFileError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message.substr(0, 300);
    EXPECT_EQ(message.rfind("mutant: $", 0), 0u) << message.substr(0, 300);
    EXPECT_LT(message.size(), 1000u) << message.substr(0, 300);
    return message;
  }
  ADD_FAILURE() << "accepted: " << text.substr(0, 300);
  return {};
}

// Nesting from a few levels to 200,000 (a recursive reader or describer runs
// out of stack near 55,000, under ASan near 5,000), of arrays, objects or
// both, where a point, a number or the whole document is expected.
TEST(SceneFileFuzz, DeepNestingIsRejectedAtTheLimitWithItsPath) {
  std::mt19937 rng(20261201);
  const int depths[] = {scenes::SceneLimits::nestingDepth + 1, 100, 5000, 55000, 200000};
  for (int k = 0; k < 30 / kCaseDivisor; ++k) {
    const int depth = depths[k % std::size(depths)];
    const int style = std::uniform_int_distribution<int>(0, 2)(rng);  // arrays, objects, alternating
    std::string open, close;
    for (int level = 0; level < depth; ++level) {
      const bool array = style == 0 || (style == 2 && level % 2 == 0);
      open += array ? "[" : "{\"a\":";
      close.insert(close.begin(), array ? ']' : '}');
    }
    const std::string value = open + close;
    const std::string texts[] = {
        "{\"particles\": [{\"position\": " + value + ", \"mass\": 1}]}",
        "{\"dt\": " + value + ", \"particles\": []}",
        value,
    };
    const std::string& text = texts[k % std::size(texts)];
    const std::string message = rejection(text);
    EXPECT_NE(message.find("expected at most 64 levels of nested arrays and objects"), std::string::npos)
        << message.substr(0, 300);
    if (HasFailure()) return;
  }
  // At the limit itself the depth is accepted and the value judged on its type.
  std::string atLimit = "{\"particles\": [{\"position\": ";
  for (int level = 3; level < scenes::SceneLimits::nestingDepth; ++level) atLimit += "[";
  atLimit += std::string(scenes::SceneLimits::nestingDepth - 3, ']') + ", \"mass\": 1}]}";
  EXPECT_NE(rejection(atLimit).find("$.particles[0].position: expected a point [x, y], got [[[["), std::string::npos);
}

// Objects with up to 100,000 keys, at the top level, in a particle and in the
// solver, with and without a duplicate: parsed in time linear in the keys (a
// quadratic parser takes minutes over these), rejected with a short message;
// a duplicate is rejected with its path.
TEST(SceneFileFuzz, ManyKeysParseAndDuplicatesAreRejectedWithTheirPath) {
  std::mt19937 rng(20261202);
  const int counts[] = {2, 10, 1000, 20000, 100000};
  int parsedLarge = 0;
  for (int k = 0; k < 20; ++k) {
    const int count = counts[k % std::size(counts)];
    const bool duplicate = k % 2 == 1;
    const int repeated = std::uniform_int_distribution<int>(0, count - 1)(rng);
    std::string members;
    for (int key = 0; key < count; ++key) members += "\"k" + std::to_string(key) + "\": 1, ";
    if (duplicate) members += "\"k" + std::to_string(repeated) + "\": 2, ";
    const std::string texts[] = {
        "{" + members + "\"particles\": []}",
        "{\"particles\": [{" + members + "\"position\": [0, 0], \"mass\": 1}]}",
        "{\"solver\": {" + members + "\"tolerance\": 1e-8}, \"particles\": []}",
    };
    const std::string paths[] = {"$", "$.particles[0]", "$.solver"};
    const std::size_t where = k % std::size(texts);
    const std::string message = rejection(texts[where]);
    const std::string expected = duplicate ? paths[where] + ".k" + std::to_string(repeated) + ": duplicate key"
                                           : paths[where] + ".k0: unknown field";
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    if (HasFailure()) return;
    parsedLarge += count == 100000;
  }
  EXPECT_EQ(parsedLarge, 4);
}

// Sizes beyond the documented limits, in files and in every integer parameter
// of every built-in scene: rejected before anything is allocated (a scene of
// 2^31 particles would throw std::bad_alloc or take minutes), never thrown as
// anything but the documented errors.
TEST(SceneFileFuzz, SizesBeyondTheLimitsAreRejected) {
  using scenes::SceneLimits;
  // Every built-in scene's integer parameters at huge values, alone and together.
  const long long huge[] = {std::numeric_limits<int>::max(), 100000000, 1000000, SceneLimits::particles + 1};
  std::mt19937 rng(20261203);
  int rejected = 0;
  // The size parameters of the built-in scenes (cloth's links is 4 or 8, a choice, not a size).
  const std::map<std::string, std::vector<std::string>> sizes = {
      {"cloth", {"width", "height"}}, {"hair", {"curls", "particles"}}, {"wire", {"beads"}},
      {"rod-chain", {"links"}},       {"test-chain", {"cl"}},           {"taut-chain", {"links"}},
  };
  for (const auto& [scene, names] : sizes) {
    for (int k = 0; k < 8; ++k) {
      std::map<std::string, std::string> overrides;
      for (const std::string& name : names)
        if (k % 2 == 0 || overrides.empty())
          overrides[name] = std::to_string(huge[std::uniform_int_distribution<std::size_t>(0, std::size(huge) - 1)(rng)]);
      try {
        scenes::buildScene(scene, overrides);
        ADD_FAILURE() << scene << " built with " << overrides.begin()->first << "=" << overrides.begin()->second;
      } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("exceeds the limit of"), std::string::npos) << e.what();
        ++rejected;
      }
      if (HasFailure()) return;
    }
  }
  EXPECT_GT(rejected, 30);

  // Files: too many particles, and too many constraints on one particle.
  const auto wires = [](int count) {
    std::string text = "{\"particles\": [{\"position\": [0.5, 0], \"mass\": 1}], \"constraints\": [";
    for (int k = 0; k < count; ++k)
      text += std::string(k ? "," : "") + "{\"type\": \"circular-wire\", \"particle\": 0, \"centre\": [0, 0], \"radius\": 0.5}";
    return text + "]}";
  };
  EXPECT_EQ(loadAndStep(wires(static_cast<int>(SceneLimits::constraintsPerParticle))), Outcome::SteppedFinite);
  for (int count : {65, 1000, 40000})
    EXPECT_NE(rejection(wires(count)).find("$.constraints[64]: particle 0 has more than the limit of 64 constraints"),
              std::string::npos);
  std::string many = "{\"particles\": [";
  for (long long k = 0; k <= SceneLimits::particles; ++k) many += std::string(k ? "," : "") + "{\"position\":[0,0],\"mass\":1}";
  EXPECT_NE(rejection(many + "]}").find("$.particles: 100001 particles exceed the limit of 100000"), std::string::npos);
}

// Paths that are not regular files, or too large: refused with one line,
// never read forever (/dev/zero), waited on (a FIFO with no writer) or read
// as an empty scene (a directory).
TEST(SceneFileFuzz, OnlyRegularFilesWithinTheSizeLimitAreRead) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("scene-file-fuzz-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string fifo = (dir / "fifo").string(), big = (dir / "big.json").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  {
    std::ofstream(big) << "{}";
  }
  std::filesystem::resize_file(big, scenes::SceneLimits::fileBytes + 1);  // sparse
  const std::pair<std::string, std::string> cases[] = {
      {"/dev/zero", "not a regular file"},
      {"/dev/null", "not a regular file"},
      {"/dev/full", "not a regular file"},
      {fifo, "not a regular file"},
      {dir.string(), "a directory, not a regular file"},
      {"/", "a directory, not a regular file"},
      {big, "larger than the limit of 67108864 bytes"},
      {(dir / "missing.json").string(), "No such file or directory"},
  };
  for (const auto& [path, reason] : cases) {
    if (!std::filesystem::exists(path)) continue;
    try {
      scenes::loadSceneFile(path);
      ADD_FAILURE() << path << " was read";
    } catch (const scenes::SceneFileError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message, path + ": cannot read the file (" + reason + ")");
    }
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
