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
// parameters, paths that are not regular files (devices, FIFOs, directories,
// oversize files), documents of millions of tiny values, colliders at every
// scale a double holds, particles starting inside colliders (the broad
// phase against every pair) and random parameters of every built-in scene
// (each starts clear of its colliders or is refused, and its export reads back).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <cmath>
#include <optional>
#include <set>

#include <sys/stat.h>
#include <unistd.h>
#include <fstream>
#include <random>
#include <sstream>

#include "particles/constants.h"
#include "particles/integrator.h"
#include "scene.h"
#include "scene_file/scene_file.h"
#include "scene_limits.h"
#include "starting_overlap.h"
#include "test_support.h"

namespace {

using scenes::Json;

enum class Outcome { Rejected, SteppedFinite, CaughtNonFinite };

// The scene of a text, or none when the reader rejects it; a rejection's
// message is checked to be one line naming the source and a JSON path.
std::optional<scenes::Scene> readMutant(const std::string& text) {
  try {
    return scenes::readScene(text, "mutant");
  } catch (const scenes::SceneFileError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.rfind("mutant: $", 0), 0u) << message;
    return std::nullopt;
  }
}

Outcome loadAndStep(const std::string& text) {
  std::optional<scenes::Scene> read = readMutant(text);
  if (!read) return Outcome::Rejected;
  scenes::Scene& scene = *read;
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

// The sanitizer build takes the first third of the cases (1,000 mutants, every
// nesting depth twice); the Release run takes them all.
constexpr int kCaseDivisor = test_support::kSanitizerBuild ? 3 : 1;

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

// Documents of millions of tiny values ("[[],[],...]" is three bytes of
// text and some 70 bytes of document a value; a 64 MiB file of them peaked at
// 1.6 GB before it was refused): refused at SceneLimits::jsonValues, while
// they are parsed, with the path of the first value past it.
TEST(SceneFileFuzz, DocumentsOfTinyValuesAreRefusedAtTheValueLimit) {
  const long long limit = scenes::SceneLimits::jsonValues;
  struct Shape {
    const char* element;  // one element of the long array
    int values;           // values it holds
  };
  const Shape shapes[] = {{"[]", 1}, {"[0,0]", 3}};
  const int count = kCaseDivisor == 1 ? static_cast<int>(std::size(shapes)) : 1;
  for (int k = 0; k < count; ++k) {
    const Shape& shape = shapes[k];
    const long long elements = limit / shape.values + 1;  // with the array itself, past the limit
    const std::string element = std::string(",") + shape.element;
    std::string text = "{\"particles\": [], \"forces\": [";
    text.reserve(text.size() + static_cast<std::size_t>(elements) * element.size() + 8);
    text += shape.element;
    for (long long e = 1; e < elements; ++e) text += element;
    text += "]}";
    const std::string message = rejection(text);
    EXPECT_NE(message.find("expected at most " + std::to_string(limit) + " JSON values in a scene file"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("mutant: $.forces["), std::string::npos) << message;
  }
}

// A collider of every kind at every scale a double holds: its position 10^a
// from the origin, its size 10^b, a and b drawn from [-330, 308] (half of
// them from [-90, 90], about the limits). One whose
// numbers the contact arithmetic cannot hold is refused with one line; every
// other one stops a particle thrown at it from just outside (a floor with
// corners at 1e200 let it fall through; a box of side 5e-324 made it NaN).
TEST(SceneFileFuzz, CollidersAtEveryScaleAreRefusedOrStopAParticle) {
  std::mt19937 rng(20261215);
  const auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  // Half the exponents over every double, half about the limits of 1e±75.
  const auto power = [&] {
    return std::pow(10.0, std::floor(uniform(0.0, 1.0) < 0.5 ? uniform(-330.0, 309.0) : uniform(-90.0, 90.0)));
  };
  int refused = 0, held = 0;
  for (int k = 0; k < 600 / kCaseDivisor; ++k) {
    const double place = power(), size = power() * uniform(0.5, 2.0);
    const Eigen::Vector2d c = place * Eigen::Vector2d(uniform(-1.0, 1.0), uniform(-1.0, 1.0));
    const auto point = [](const Eigen::Vector2d& p) { return Json::array({p.x(), p.y()}); };
    Json collider;
    Eigen::Vector2d inward(0.0, -1.0), top = c;  // the particle comes from above the collider's top
    switch (k % 5) {
      case 0: {
        const Eigen::Vector2d half(size, size * uniform(0.2, 1.0));
        collider = {{"type", "box"}, {"min", point(c - half)}, {"max", point(c + half)}};
        top = c + Eigen::Vector2d(0.0, half.y());
        break;
      }
      case 1: {
        const int n = 3 + k % 6;
        Json vertices = Json::array();
        for (int v = 0; v < n; ++v) {
          const double angle = 0.5 * particles::kPi + 2.0 * particles::kPi * v / n;  // vertex 0 on top
          vertices.push_back(point(c + size * Eigen::Vector2d(std::cos(angle), std::sin(angle))));
        }
        collider = {{"type", "polygon"}, {"vertices", vertices}};
        top = c + Eigen::Vector2d(0.0, size);
        break;
      }
      case 2:
        collider = {{"type", "capsule"}, {"from", point(c - Eigen::Vector2d(size, 0.0))},
                    {"to", point(c + Eigen::Vector2d(size, 0.0))}, {"radius", 0.3 * size}};
        top = c + Eigen::Vector2d(0.0, 0.3 * size);
        break;
      case 3:
        collider = {{"type", "disc"}, {"centre", point(c)}, {"radius", size}};
        top = c + Eigen::Vector2d(0.0, size);
        break;
      default: {
        const double angle = uniform(0.0, 2.0 * particles::kPi);
        const Eigen::Vector2d n(std::cos(angle), std::sin(angle));
        collider = {{"type", "halfPlane"}, {"point", point(c)}, {"normal", point(n)}};
        inward = -n;
        top = c;
      }
    }
    const double dt = 0.01, gap = size;
    const Eigen::Vector2d start = top - gap * inward, velocity = 3.0 * gap / dt * inward;
    const Json document = {{"dt", dt},
                           {"particles", Json::array({{{"position", point(start)}, {"mass", 1}, {"velocity", point(velocity)}}})},
                           {"colliders", Json::array({collider})}};
    const std::string text = document.dump();
    std::optional<scenes::Scene> read = readMutant(text);
    if (!read) {
      ++refused;
      continue;
    }
    scenes::Scene& scene = *read;
    // Accepted: the particle, thrown at the collider from a gap of its size,
    // stays outside it to rounding at every step.
    const particles::Collider& shape = scene.system->colliders().at(0);
    const auto integrator = particles::makeIntegrator(scene.integrator);
    for (int step = 0; step < 5 && !HasFailure(); ++step) {
      scene.system->step(*integrator, scene.dt);
      const Eigen::Vector2d p = scene.system->position(0);
      ASSERT_TRUE(p.allFinite()) << text;
      EXPECT_GE(shape.distance(p).distance, -scenes::startingOverlapTolerance(p)) << "step " << step << ": " << text;
    }
    if (HasFailure()) return;
    ++held;
  }
  std::printf("[ fuzz     ] colliders at every scale: %d refused, %d stopped the particle\n", refused, held);
  EXPECT_GT(refused, 0);
  EXPECT_GT(held, 0);
}

// Particles (points and discs) scattered over and around colliders of every
// kind: the check's broad phase finds the same first overlap as a test of
// every particle against every collider with the same definition.
TEST(SceneFileFuzz, TheStartingOverlapBroadPhaseFindsWhatEveryPairFinds) {
  std::mt19937 rng(20261216);
  const auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  int found = 0;
  for (int k = 0; k < 300 / kCaseDivisor; ++k) {
    particles::ParticleSystem system;
    const double spread = std::pow(10.0, uniform(-2.0, 3.0));
    const int particles = 1 + static_cast<int>(uniform(0.0, 400.0));
    for (int i = 0; i < particles; ++i) {
      const Eigen::Vector2d x = spread * Eigen::Vector2d(uniform(-1.0, 1.0), uniform(-1.0, 1.0));
      const int p = system.addParticle(k % 7 == 0 ? Eigen::Vector2d(x.x(), 0.0) : x, 1.0);  // some all on one line
      if (uniform(0.0, 1.0) < 0.3) system.setCollidable(p, spread * uniform(1e-4, 0.05));
    }
    const int colliders = static_cast<int>(uniform(0.0, 6.0));
    for (int c = 0; c < colliders; ++c) {
      const Eigen::Vector2d centre = 1.5 * spread * Eigen::Vector2d(uniform(-1.0, 1.0), uniform(-1.0, 1.0));
      const double size = spread * std::pow(10.0, uniform(-3.0, 0.0));
      switch (static_cast<int>(uniform(0.0, 5.0))) {
        case 0: system.addCollider(particles::Collider::box(centre, centre + Eigen::Vector2d(size, 0.5 * size))); break;
        case 1: system.addCollider(particles::Collider::disc(centre, size)); break;
        case 2: system.addCollider(particles::Collider::capsule(centre, centre + Eigen::Vector2d(size, size), 0.1 * size)); break;
        case 3:
          system.addCollider(particles::Collider::polygon(
              {centre, centre + Eigen::Vector2d(size, 0.0), centre + Eigen::Vector2d(0.2 * size, size)}));
          break;
        default: system.addCollider(particles::Collider::halfPlane(centre * 1.5, Eigen::Vector2d(uniform(-1.0, 1.0), 1.0)));
      }
    }
    std::optional<scenes::StartingOverlap> expected;
    for (int i = 0; i < system.size() && !expected; ++i)
      for (std::size_t c = 0; c < system.colliders().size() && !expected; ++c) {
        const double depth = system.radii()[i] - system.colliders()[c].distance(system.position(i)).distance;
        if (depth > scenes::startingOverlapTolerance(system.position(i))) expected = scenes::StartingOverlap{i, c, depth};
      }
    const std::optional<scenes::StartingOverlap> got = scenes::firstStartingOverlap(system);
    ASSERT_EQ(got.has_value(), expected.has_value()) << "case " << k;
    if (!got) continue;
    EXPECT_EQ(got->particle, expected->particle) << "case " << k;
    EXPECT_EQ(got->collider, expected->collider) << "case " << k;
    EXPECT_EQ(got->depth, expected->depth) << "case " << k;
    if (HasFailure()) return;
    ++found;
  }
  EXPECT_GT(found, 20);
}

// Random parameters of every built-in scene (each number the default times
// 10^±1, with its sign flipped now and then, the other preset's, or in
// [-90, 90] for an angle; sizes small): the scene is refused with one line,
// or it starts with every particle clear of its colliders and its export
// reads back (cloth swing=-30 started inside its wall, gaining 45% of its
// energy in the first step, and exported a file the reader refused).
TEST(SceneFileFuzz, EveryBuiltInParameterSetStartsClearOrIsRefusedAndItsExportReadsBack) {
  std::mt19937 rng(20261217);
  const auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  const std::set<std::string> sizes = {"width", "height", "curls", "particles", "beads", "links", "cl"};
  int built = 0, refused = 0;
  for (int k = 0; k < 400 / kCaseDivisor; ++k) {
    const scenes::SceneInfo& info = scenes::sceneTable()[k % scenes::sceneTable().size()];
    std::map<std::string, std::string> overrides;
    for (const scenes::ParamSpec& spec : info.params) {
      if (uniform(0.0, 1.0) < 0.4) continue;
      const std::string& value = spec.values.at(static_cast<std::size_t>(uniform(0.0, 1.0) < 0.5));
      char* end = nullptr;
      const double number = std::strtod(value.c_str(), &end);
      if (value.empty() || *end != '\0') {  // a word: the one preset's or the other's
        overrides[spec.name] = value;
      } else if (info.name == std::string("cloth") && spec.name == "links") {
        overrides[spec.name] = uniform(0.0, 1.0) < 0.5 ? "4" : "8";
      } else if (sizes.count(spec.name)) {
        overrides[spec.name] = std::to_string(static_cast<int>(uniform(1.0, 24.0)));
      } else if (spec.name.find("angle") != std::string::npos || spec.name == "swing") {
        overrides[spec.name] = std::to_string(uniform(-90.0, 90.0));
      } else if (spec.name == "edge-contacts" || spec.name == "wind-seed") {
        overrides[spec.name] = value;  // a choice, a seed
      } else {
        const double sign = uniform(0.0, 1.0) < 0.1 ? -1.0 : 1.0;
        char text[32];
        std::snprintf(text, sizeof text, "%.6g", sign * number * std::pow(10.0, uniform(-1.0, 1.0)));
        overrides[spec.name] = text;
      }
    }
    std::string given = info.name;
    for (const auto& [key, value] : overrides) given += " " + key + "=" + value;
    scenes::Scene scene;
    try {
      scene = scenes::buildScene(info.name, overrides);
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      ++refused;
      continue;
    }
    EXPECT_FALSE(scenes::firstStartingOverlap(*scene.system)) << given;
    try {
      const scenes::Scene back = scenes::readScene(scenes::writeScene(scene), "export");
      EXPECT_EQ(back.system->size(), scene.system->size()) << given;
    } catch (const scenes::SceneFileError& e) {
      ADD_FAILURE() << given << ": the export does not read back: " << e.what();
    }
    if (HasFailure()) return;
    ++built;
  }
  std::printf("[ fuzz     ] built-in parameters: %d built and read back, %d refused\n", built, refused);
  EXPECT_GT(built, 150 / kCaseDivisor);
  EXPECT_GT(refused, 0);
}

}  // namespace
