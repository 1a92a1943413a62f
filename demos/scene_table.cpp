#include <algorithm>
#include <optional>
#include <set>
#include <stdexcept>

#include "join_names.h"
#include "particles/check.h"
#include "scene.h"
#include "scenes/capstan.h"
#include "scenes/cloth.h"
#include "scenes/hair.h"
#include "scenes/hourglass.h"
#include "scenes/newtons_cradle.h"
#include "scenes/oscillator.h"
#include "scenes/param_fields.h"
#include "scenes/pendulum.h"
#include "scenes/rod_chain.h"
#include "scenes/rope_bridge.h"
#include "scenes/soft_body.h"
#include "scenes/taut_chain.h"
#include "scenes/test_chain.h"
#include "scenes/wire.h"
#include "starting_overlap.h"

namespace scenes {

namespace {
// Adapts a typed builder, Scene build(const Params&), to the table's
// Scene build(const SceneParams&).
template <class Params, Scene (*Build)(const Params&)>
Scene buildFromValues(const SceneParams& values) {
  return Build(readParams<Params>(values));
}

template <class Params, Scene (*Build)(const Params&)>
SceneInfo entry(const char* name, const char* summary, const char* hint) {
  return {name, summary, hint, paramSpecs<Params>(), buildFromValues<Params, Build>};
}

// A gallery scene (SceneInfo::gallery): after the number keys' in the demo's list.
template <class Params, Scene (*Build)(const Params&)>
SceneInfo galleryEntry(const char* name, const char* summary, const char* hint) {
  SceneInfo info = entry<Params, Build>(name, summary, hint);
  info.gallery = true;
  return info;
}
}  // namespace

const std::vector<SceneInfo>& sceneTable() {
  static const std::vector<SceneInfo> table = {
      entry<ClothParams, buildCloth>(
          "cloth", "spring cloth on a curtain rail, released swung aside; a big wall left and a nail right",
          "try this: drag the cloth's hem onto the nail, or slide the whole curtain along its rail"),
      entry<HairParams, buildHair>(
          "hair", "strands of springs and angular springs, hanging and colliding: ringlets, or the seed preset's zigzag",
          "try this: pull a curl's tip down and let go: it springs back into its ringlet"),
      entry<WireParams, buildWire>(
          "wire", "beads on circular wires, coupled by soft springs",
          "try this: watch the swing pass from bead to bead along the springs; stop one bead with the mouse"),
      entry<RodChainParams, buildRodChain>(
          "rod-chain", "a chain of rods hanging from a bead on a circular wire",
          "try this: drag the chain's tip around the wire; compare rk4 with euler (v) to see the rods stretch"),
      entry<TestChainParams, buildTestChain>(
          "test-chain", "the integrator test: a pinned chain of rods released horizontally",
          "try this: press v to compare integrators on the falling chain, then + to see which survives a larger dt"),
      entry<TautChainParams, buildTautChain>(
          "taut-chain", "a straight chain of rods between two wires (the solver's singular case)",
          "try this: raise dt with + and watch the straight chain where the solve is singular"),
      entry<OscillatorParams, buildOscillator>(
          "oscillator", "a mass on a damped spring, closed-form solution",
          "try this: compare euler with rk4 (v): euler's swing grows while the closed form decays"),
      entry<PendulumParams, buildPendulum>(
          "pendulum", "a bead on a circular wire released at a large angle",
          "try this: drag the bead higher and let go: the period grows with the amplitude"),
      // The gallery: things meeting each other and the walls.
      galleryEntry<HourglassParams, buildHourglass>(
          "hourglass", "sand in an hourglass: discs pouring through the neck and heaping below",
          "try this: press r and watch the stream, or narrow the neck (panel) until the grains jam"),
      galleryEntry<NewtonsCradleParams, buildNewtonsCradle>(
          "newtons-cradle", "Newton's cradle: elastic balls on rods pass the first ball's swing to the last",
          "try this: set restitution to 0.9 in the panel and watch the swing pass on and die away; or drag the last ball"),
      galleryEntry<CapstanParams, buildCapstan>(
          "capstan", "a rope over a fixed pulley: friction holds loads up to the ratio e^(mu theta)",
          "try this: set ratio above e^(mu pi) in the panel and the heavy load slides down; or pull a load"),
      galleryEntry<RopeBridgeParams, buildRopeBridge>(
          "rope-bridge", "balls dropped onto a sagging rope bridge of disc planks",
          "try this: drag a ball up and drop it on the bridge, or pin a plank (right drag) and watch it sway"),
      galleryEntry<SoftBodyParams, buildSoftBody>(
          "soft-body", "two gas-filled rings (pressure inside springs) dropped onto a floor and a ramp",
          "try this: squash a ball with the mouse: Boyle's law pushes back harder as its area shrinks"),
  };
  for (const SceneInfo& info : table)
    for (const ParamSpec& spec : info.params)
      if (spec.values.size() != presetTable().size())
        throw std::logic_error(std::string("scene '") + info.name + "' parameter '" + spec.name +
                               "' lacks a value for every preset");
  return table;
}

namespace {

// Parameters that start a particle inside a collider (starting_overlap.h) are
// refused as the scene-file reader refuses such a file, so that a built-in
// scene never starts gaining energy from a push out of a wall and every
// export reads back.
void refuseStartingOverlap(const Scene& scene, const std::map<std::string, std::string>& overrides) {
  const std::optional<StartingOverlap> overlap = firstStartingOverlap(*scene.system);
  if (!overlap) return;
  std::string given;
  for (const auto& [key, value] : overrides) given += (given.empty() ? "" : " ") + key + "=" + value;
  throw std::invalid_argument(
      "particle " + std::to_string(overlap->particle) + " starts inside collider " + std::to_string(overlap->collider) +
      " (a " + particles::colliderName(scene.system->colliders()[overlap->collider].shape) + ") by " +
      particles::formatValue(overlap->depth) + " with " + (given.empty() ? "the preset's parameters" : given) +
      ": a contact cannot push it out without adding energy; choose parameters that start every particle "
      "clear of the colliders");
}

}  // namespace

const SceneInfo* findScene(const std::string& name) {
  for (const SceneInfo& info : sceneTable())
    if (name == info.name) return &info;
  return nullptr;
}

Scene buildScene(const std::string& name, const std::map<std::string, std::string>& overrides,
                 const std::string& preset) {
  presetIndex(preset);  // an unknown preset is reported before an unknown scene
  const SceneInfo* info = findScene(name);
  if (!info) throw std::invalid_argument("unknown scene '" + name + "' (valid: " + joinNames(sceneTable()) + ")");
  try {
    Scene scene = info->build(SceneParams(info->params, overrides, preset));
    refuseStartingOverlap(scene, overrides);
    return scene;
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("scene '" + name + "': " + e.what());
  }
}

std::vector<std::array<int, 2>> faceEdges(const Scene& scene) {
  std::vector<std::array<int, 2>> edges;
  std::set<std::array<int, 2>> seen;
  for (const std::array<int, 4>& face : scene.faces)
    for (int k = 0; k < 4; ++k) {
      const int a = face[k], b = face[(k + 1) % 4];
      const std::array<int, 2> edge{std::min(a, b), std::max(a, b)};
      if (seen.insert(edge).second) edges.push_back(edge);
    }
  return edges;
}

}  // namespace scenes
