#include "lab/chain.h"

#include "lab/lab_scene.h"
#include "particles/constraints/rod.h"

namespace lab {

scenes::Scene buildChain(const ChainSpec& spec) {
  std::map<std::string, std::string> params = spec.extra;
  params["cl"] = std::to_string(spec.length);
  params["rod"] = spec.rodForm;
  return buildLabScene("test-chain", params);
}

double chainRodLength(const scenes::Scene& chain) {
  for (const auto& c : chain.system->constraints())
    if (auto* rod = dynamic_cast<const particles::RodConstraint*>(c.get())) return rod->length();
  throw std::logic_error("the test chain has no rod");
}

}  // namespace lab
