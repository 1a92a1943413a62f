#pragma once
// The test chain as the experiments build it: the built-in `test-chain` scene
// with its parameters set by name.
#include <map>
#include <string>

#include "scene.h"

namespace lab {

struct ChainSpec {
  ChainSpec(int particles, std::string rod = "squared") : length(particles), rodForm(std::move(rod)) {}
  int length;                                // particles, cl
  std::string rodForm;                       // "squared" | "root"
  std::map<std::string, std::string> extra;  // further test-chain parameters
};

scenes::Scene buildChain(const ChainSpec& spec);

// Rod length and gravity of the test chain, for the dimensionless step dt·√(g/r).
double chainRodLength(const scenes::Scene& chain);

}  // namespace lab
