#pragma once
#include "scene.h"
#include "scenes/world.h"

namespace scenes {

// A rope bridge: a chain of planks (particles joined by stiff damped
// springs, every one a disc) slung between two pinned anchors with some
// sag, and `balls` heavy balls dropped onto it one after another. The balls
// roll down into the dip, the bridge sways and bounces under them; the
// planks' discs touch, so no ball falls through between two.
struct RopeBridgeParams {
  int planks = 24;                 // particles between the anchors
  double span = 1.2;               // between the anchors, m
  double slack = 0.06;             // the rope's extra length over the span, as a fraction
  double plankMass = 0.02;         // kg
  double stiffness = 3000.0;       // spring k_s, N/m
  double damping = 2.0;            // spring k_d, N s/m
  int balls = 3;
  double ballRadius = 0.05;        // m
  double ballMass = 0.3;           // kg
  double restitution = 0.3;        // e of ball–plank and ball–ball impacts
  double gravity = kEarthGravity;  // m/s²
  double dt = 0.001;               // the step the scene runs with, s

  template <class Visit>
  void visit(Visit&& field) {
    field("planks", planks, "planks (disc particles) between the anchors");
    field("span", span, "distance between the anchors, m");
    field("slack", slack, "extra rope length over the span, as a fraction");
    field("plank-mass", plankMass, "mass of each plank, kg");
    field("stiffness", stiffness, "spring k_s between planks, N/m");
    field("damping", damping, "spring k_d, N s/m");
    field("balls", balls, "balls dropped onto the bridge");
    field("ball-radius", ballRadius, "ball radius, m");
    field("ball-mass", ballMass, "mass of each ball, kg");
    field("restitution", restitution, "restitution e of the impacts, in [0, 1]");
    field("gravity", gravity, "downward acceleration g, m/s^2");
  }
  void validate() const;
  static RopeBridgeParams seed();  // preset "seed": the defaults under the seed's gravity
};

Scene buildRopeBridge(const RopeBridgeParams& p);

}  // namespace scenes
