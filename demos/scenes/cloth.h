#pragma once
#include "scene.h"
#include "scenes/wind_and_tearing.h"
#include "scenes/world.h"

namespace scenes {

// The cloth testing ground: a width × height grid of particles joined by
// damped springs, its top row sliding on a horizontal line like a curtain on
// a rail, under gravity, beside a big wall on the left that stops most of the
// cloth and a small "nail" on the right it can catch on. The cloth swings by
// `swing` with every spring at its rest length at the start: the 4-way
// cloth is released at rest with every column turned by that angle about its
// particle on the rail (a shear, which 4-way springs do not resist), so it
// swings like a curtain pushed aside; the 8-way cloth, whose diagonals do
// resist shear (that shear would stretch one diagonal of each cell by 16% and
// shorten the other by 19% at 20°), hangs straight and is released moving,
// each row at ω times its depth, with the ω that would lift a rigid column
// on a fixed pin to the swing angle: ½ (m H²/3) ω² = m g (H/2)(1 − cos swing);
// on its sliding rail that push both swings the curtain and slides it along.
//
// Defaults: the top spring of each column carries the weight of the
// height − 1 particles below it, stretching by (height − 1) m g / k_s =
// 2.2 mm, 4.4% of rest (at most 10% at rest is the target); the fastest
// spring mode, ω ≈ √(8 k_s/m) = 570 rad/s, keeps RK4 (|ω dt| < 2.8) stable
// below dt ≈ 0.005 s, and dt = 0.002 s leaves it a factor 2.4. The swing
// of a 0.45 m curtain takes about 1.1 s; air drag k_d/m = 0.4/s lets it
// settle within seconds.
//
// Folds: a grid of springs rests as well turned over as the right way round,
// so a cloth pulled over itself could stay folded, its folded faces
// inverted. A face-area floor (particles/forces/face_area.h) pushes any face
// back once its area drops below area-floor (half) of its rest area, with
// area-stiffness k = 2 k_s: a face turned over entirely is pushed back at
// each corner with k (1 + s) r/√2 ≈ 21 N, as much as a spring stretched by two
// rest lengths. The default 8-way cloth folded in half (36 of its 81 faces
// turned over) opens within half a second at k ≥ 150 N/m and stays folded at
// 100 N/m (tests/test_scenes.cpp holds it to both ends), so k = 400 N/m
// leaves a margin of 2.7 to 4. A
// face above the floor feels nothing, so the hanging and swinging cloth, its
// rest strain and its stable dt are as without it.
//
// Wind and tearing (wind_and_tearing.h) are off by default: the wind pushes
// on the face sides (the structural springs), and the springs tear beyond
// tear-strain.
struct ClothParams : WindTearParams {
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
  double areaStiffness = 400.0;    // k of the face-area floor, N/m (0: none)
  double areaFloor = 0.5;          // s: the fraction of a face's rest area below which it is pushed
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
    field("swing", swing, "release angle of the cloth's columns from hanging straight, degrees (+: hem to the right; 8-way: hangs straight, released with the push that swings a pinned column to it)");
    field("drag", drag, "air drag k_d on every particle, N s/m (0: none)");
    field("edge-contacts", edgeContacts, "1: the cloth's edges, not only its particles, meet the wall and nail; 0: particles only");
    field("area-stiffness", areaStiffness, "k of the faces' area floor, N/m: a face below area-floor of its rest area (folded over, crushed) is pushed back (0: none)");
    field("area-floor", areaFloor, "the fraction of a face's rest area below which the area floor pushes, in [0, 1]");
    visitWindTear(field);
  }
  void validate() const;
  static ClothParams seed();  // preset "seed": the seed report's values
};

Scene buildCloth(const ClothParams& p);

// The stiff cloth of the small-steps comparison (an n×n 8-way cloth with
// k_s = 4e5, k_d = 0.5 under g = 9.8, hanging straight without drag, edge
// contacts or area floor; mass and spacing as the defaults):
// k_s h²/m = 5.6e2 at h = 1/60, so RK4 needs dt < 1/1000 on it, while xpbd
// steps it at 60 Hz. The demo runs it at n = 64, the benchmark at n = 128.
ClothParams stiffClothParams(int size);

}  // namespace scenes
