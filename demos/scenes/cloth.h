#pragma once
#include "scene.h"

namespace scenes {

// The report's cloth testing ground: a width × height grid of particles joined
// by damped springs, its top row sliding on a horizontal line like a curtain,
// under gravity, beside a big wall on the left that stops most of the cloth
// and a small "nail" on the right it can catch on.
struct ClothParams {
  int width = 10, height = 10;
  int links = 4;
  double rest = 0.05;
  double stiffness = 0.9;
  double damping = 0.6;
  double mass = 0.2;
  double gravity = 0.05;

  double dt = 0.01;  // the step the scene runs with, s

  template <class Visit>
  void visit(Visit&& field) {
    field("width", width, "particles across");
    field("height", height, "particles down");
    field("links", links, "4: springs to the 4 neighbours; 8: also the diagonals, at sqrt(2)*rest");
    field("rest", rest, "spring rest length between neighbours, world units");
    field("stiffness", stiffness, "spring k_s, force/length");
    field("damping", damping, "spring k_d, force/speed");
    field("mass", mass, "mass of each particle");
    field("gravity", gravity, "downward acceleration, world units/s^2");
  }
  void validate() const;
  static ClothParams seed();  // preset "seed": the seed report's values
};

Scene buildCloth(const ClothParams& p);

// The stiff cloth of the small-steps comparison (an n×n 8-way cloth with
// k_s = 4e5, k_d = 0.5 under g = 9.8; mass and spacing as the defaults):
// k_s h²/m = 5.6e2 at h = 1/60, so RK4 needs dt < 1/1000 on it, while xpbd
// steps it at 60 Hz. The demo runs it at n = 64, the benchmark at n = 128.
ClothParams stiffClothParams(int size);

}  // namespace scenes
