#pragma once
#include "scene.h"
#include "scenes/world.h"

namespace scenes {

// The cloth testing ground: a width × height grid of particles joined by
// damped springs, its top row sliding on a horizontal line like a curtain on
// a rail, under gravity, beside a big wall on the left that stops most of the
// cloth and a small "nail" on the right it can catch on. The cloth is
// released at rest swung out by `swing`: every column turned by that angle
// about its particle on the rail (a shear, which 4-way springs do not resist),
// so it swings like a curtain pushed aside.
//
// Defaults: the top spring of each column carries the weight of the
// height − 1 particles below it, stretching by (height − 1) m g / k_s =
// 2.2 mm, 4.4% of rest (at most 10% at rest is the target); the fastest
// spring mode, ω ≈ √(8 k_s/m) = 570 rad/s, keeps RK4 (|ω dt| < 2.8) stable
// below dt ≈ 0.005 s, and dt = 0.002 s leaves it a factor 2.4. The swing
// of a 0.45 m curtain takes about 1.1 s; air drag k_d/m = 0.4/s lets it
// settle within seconds.
struct ClothParams {
  int width = 10, height = 10;
  int links = 4;
  double rest = 0.05;              // m
  double stiffness = 200.0;        // N/m
  double damping = 0.1;            // N·s/m
  double mass = 0.005;             // kg
  double gravity = kEarthGravity;  // m/s²
  double swing = 20.0;             // degrees
  double drag = 0.002;             // N·s/m
  int edgeContacts = 1;
  double dt = 0.002;               // the step the scene runs with, s

  template <class Visit>
  void visit(Visit&& field) {
    field("width", width, "particles across");
    field("height", height, "particles down");
    field("links", links, "4: springs to the 4 neighbours; 8: also the diagonals, at sqrt(2)*rest");
    field("rest", rest, "spring rest length between neighbours, m");
    field("stiffness", stiffness, "spring k_s, N/m");
    field("damping", damping, "spring k_d, N s/m");
    field("mass", mass, "mass of each particle, kg");
    field("gravity", gravity, "downward acceleration, m/s^2");
    field("swing", swing, "release angle of the cloth's columns from hanging straight, degrees (+: hem to the right)");
    field("drag", drag, "air drag k_d on every particle, N s/m (0: none)");
    field("edge-contacts", edgeContacts, "1: the cloth's edges, not only its particles, meet the wall and nail; 0: particles only");
  }
  void validate() const;
  static ClothParams seed();  // preset "seed": the seed report's values
};

Scene buildCloth(const ClothParams& p);

}  // namespace scenes
