#pragma once
#include "scene.h"
#include "scenes/chain_on_wires.h"

namespace scenes {

// A chain of rods hanging from a bead that rides on a circular wire, released
// horizontally at rest under gravity.
struct RodChainParams : ChainOnWiresParams {
  int links = 6;
  double length = 0.12;  // m
  double radius = 0.25;  // m

  template <class Visit>
  void visit(Visit&& field) {
    field("links", links, "number of rods");
    field("length", length, "rod length, m");
    field("radius", radius, "radius of the wire the first particle rides on, m");
    visitShared(field);
  }
  void validate() const;
  static RodChainParams seed();  // preset "seed": the seed report's values
};

Scene buildRodChain(const RodChainParams& p);

}  // namespace scenes
