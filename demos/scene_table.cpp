#include <stdexcept>

#include "join_names.h"
#include "scene.h"
#include "scenes/cloth.h"
#include "scenes/hair.h"
#include "scenes/oscillator.h"
#include "scenes/param_fields.h"
#include "scenes/pendulum.h"
#include "scenes/rod_chain.h"
#include "scenes/taut_chain.h"
#include "scenes/test_chain.h"
#include "scenes/wire.h"

namespace scenes {

namespace {
// Adapts a typed builder, Scene build(const Params&), to the table's
// Scene build(const SceneParams&).
template <class Params, Scene (*Build)(const Params&)>
Scene buildFromValues(const SceneParams& values) {
  return Build(readParams<Params>(values));
}

template <class Params, Scene (*Build)(const Params&)>
SceneInfo entry(const char* name, const char* summary) {
  return {name, summary, paramSpecs<Params>(), buildFromValues<Params, Build>};
}
}  // namespace

const std::vector<SceneInfo>& sceneTable() {
  static const std::vector<SceneInfo> table = {
      entry<ClothParams, buildCloth>("cloth", "spring cloth on a curtain rail, a big wall left and a nail right"),
      entry<HairParams, buildHair>("hair", "curls of springs and angular springs, roots on a rail, colliding"),
      entry<WireParams, buildWire>("wire", "beads on circular wires, coupled by soft springs"),
      entry<RodChainParams, buildRodChain>("rod-chain", "a chain of rods hanging from a bead on a circular wire"),
      entry<TestChainParams, buildTestChain>("test-chain", "the integrator test: a pinned chain of rods released horizontally"),
      entry<TautChainParams, buildTautChain>("taut-chain", "a straight chain of rods between two wires (the solver's singular case)"),
      entry<OscillatorParams, buildOscillator>("oscillator", "a mass on a damped spring, closed-form solution"),
      entry<PendulumParams, buildPendulum>("pendulum", "a bead on a circular wire released at a large angle"),
  };
  return table;
}

Scene buildScene(const std::string& name, const std::map<std::string, std::string>& overrides) {
  for (const SceneInfo& info : sceneTable()) {
    if (name != info.name) continue;
    try {
      return info.build(SceneParams(info.params, overrides));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("scene '" + name + "': " + e.what());
    }
  }
  throw std::invalid_argument("unknown scene '" + name + "' (valid: " + joinNames(sceneTable()) + ")");
}

}  // namespace scenes
