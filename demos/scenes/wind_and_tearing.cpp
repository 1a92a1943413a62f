#include "scenes/wind_and_tearing.h"

#include <memory>
#include <stdexcept>
#include <string>

#include "particles/check.h"
#include "particles/tearing.h"
#include "scenes/world.h"

namespace scenes {

void WindTearParams::validateWindTear() const {
  particles::requireNonNegative("wind", wind);
  // A turn either way is every direction; beyond it, degrees × π overflows
  // before the division by 180 (1e308 read as a direction of inf).
  particles::requireInRange("wind-angle", windAngle, -360.0, 360.0);
  particles::requireNonNegative("wind-drag", windDrag);
  particles::requireInRange("gust", gust, 0.0, 1.0);
  particles::requirePositive("gust-period", gustPeriod);
  if (windSeed < 0) throw std::invalid_argument("wind-seed must be >= 0, got " + std::to_string(windSeed));
  particles::requireNonNegative("tear-strain", tearStrain);
}

particles::WindSettings WindTearParams::windSettings() const {
  particles::WindSettings w;
  w.speed = wind;
  w.direction = radians(windAngle);
  w.drag = windDrag;
  w.gust = gust;
  w.gustPeriod = gustPeriod;
  w.seed = windSeed;
  return w;
}

void WindTearParams::addWindAndTearing(particles::ParticleSystem& system,
                                       std::vector<std::array<int, 2>> edges) const {
  if (wind > 0.0) system.addForce(std::make_unique<particles::WindForce>(std::move(edges), windSettings()));
  system.tearing().strain = tearStrain;
}

}  // namespace scenes
