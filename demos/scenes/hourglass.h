#pragma once
#include "scene.h"
#include "scenes/world.h"

namespace scenes {

// An hourglass: `grains` discs of radius r in the upper bulb of a glass of
// walls (capsules), pouring through a neck of width `neck` into the lower
// bulb under gravity. Grains bounce off each other with restitution e and
// slide on the glass with friction μ; with the neck a few grains wide they
// flow in a stream and heap below. Defaults: 150 grains of 2 g, r = 1 cm,
// a neck of 2.5 grain diameters: the upper bulb empties in some 3.5 s; at
// 2.25 diameters the grains arch over the neck and the flow stops part way,
// at 1.75 at once. (Grains slide on each other without friction here, so
// the heap below lies flat.)
struct HourglassParams {
  int grains = 150;
  double radius = 0.01;            // r, m
  double mass = 0.002;             // kg
  double neck = 0.05;              // width of the neck, m
  double restitution = 0.1;        // e of grain–grain impacts
  double friction = 0.3;           // μ of grains on the glass
  double gravity = kEarthGravity;  // m/s²
  double dt = 0.002;               // the step the scene runs with, s

  template <class Visit>
  void visit(Visit&& field) {
    field("grains", grains, "grains of sand (discs) in the upper bulb");
    field("radius", radius, "grain radius r, m");
    field("mass", mass, "mass of each grain, kg");
    field("neck", neck, "width of the neck, m (grains pass while it is wider than a grain)");
    field("restitution", restitution, "restitution e of grain-grain impacts, in [0, 1]");
    field("friction", friction, "Coulomb friction mu of the grains on the glass");
    field("gravity", gravity, "downward acceleration g, m/s^2");
  }
  void validate() const;
  static HourglassParams seed();  // preset "seed": the defaults under the seed's gravity
};

Scene buildHourglass(const HourglassParams& p);

}  // namespace scenes
