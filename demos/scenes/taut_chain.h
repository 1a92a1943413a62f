#pragma once
#include "scene.h"
#include "scenes/chain_on_wires.h"

namespace scenes {

// The report's explosion case: a chain of rods pulled fully straight between
// two beads that ride on circular wires, each bead at the far side of its
// wire, under gravity. While the chain is straight every rod and both wire
// normals are parallel, so J W Jᵀ loses rank: a stress test for the solver.
struct TautChainParams : ChainOnWiresParams {
  int links = 8;
  double separation = 1.2;  // m
  double radius = 0.2;      // m

  template <class Visit>
  void visit(Visit&& field) {
    field("links", links, "number of rods between the two beads");
    field("separation", separation, "distance between the two wire centres, m");
    field("radius", radius, "radius of both wires, m");
    visitShared(field);
  }
  void validate() const;
  static TautChainParams seed();  // preset "seed": the seed report's values
};

Scene buildTautChain(const TautChainParams& p);

}  // namespace scenes
