#pragma once
// What the cloth and the hair share: wind on their edges and springs that
// tear (particles/forces/wind.h, particles/tearing.h). Both are off unless a
// parameter turns them on, so a scene without them is the scene it was.
//
// The drag coefficient c (force per metre of edge per (m/s)²) is chosen so
// that a 5 m/s wind across them is felt like their weight: on the default
// cloth a 5 cm edge of 5 g particles takes c × 0.05 × 5² = 0.025 N, half the
// weight of its particle (0.049 N), and blows the curtain some 25° out; a
// 1 cm hair link of 1 g takes 0.005 N against 0.0098 N.
#include <array>
#include <vector>

#include "particles/forces/wind.h"
#include "particles/particle_system.h"

namespace scenes {

struct WindTearParams {
  double wind = 0.0;         // mean speed U, m/s (0: no wind)
  double windAngle = 0.0;    // degrees counter-clockwise from +x, the way the air moves
  double windDrag = 0.02;    // c, N per m of edge per (m/s)²
  double gust = 0.5;         // A in [0, 1]: the speed swings between (1 − A) U and (1 + A) U
  double gustPeriod = 2.0;   // s, the slowest gust
  int windSeed = 1;          // the gusts' phases
  double tearStrain = 0.0;   // springs stretched by more than this fraction tear (0: none)

  // The shared fields, after the scene's own in its visit().
  template <class Visit>
  void visitWindTear(Visit&& field) {
    field("wind", wind, "mean wind speed across the edges, m/s (0: no wind)");
    field("wind-angle", windAngle, "the way the wind blows, degrees counter-clockwise from +x, in [-360, 360] (0: to the right)");
    field("wind-drag", windDrag, "drag c of an edge across the wind: c |edge| u_n^2, N per m per (m/s)^2");
    field("gust", gust, "gust amplitude A in [0, 1]: the speed swings between (1 - A) and (1 + A) times the mean");
    field("gust-period", gustPeriod, "the slowest gust's period, s (gusts repeat exactly for one seed)");
    field("wind-seed", windSeed, "the gusts' phases, an integer >= 0");
    field("tear-strain", tearStrain, "springs stretched beyond this fraction of their rest length tear (0: none)");
  }
  void validateWindTear() const;
  particles::WindSettings windSettings() const;  // at the mean speed `wind`
  // The wind on `edges` when wind > 0, and the tearing limit.
  void addWindAndTearing(particles::ParticleSystem& system, std::vector<std::array<int, 2>> edges) const;
};

}  // namespace scenes
