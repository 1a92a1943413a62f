#include "particles/tearing.h"

#include "particles/check.h"
#include "particles/forces/spring.h"
#include "particles/particle_system.h"

namespace particles {

void TearSettings::validate() const { requireNonNegative("tear strain", strain); }

void Tearing::gather(const ParticleSystem& system) {
  springs_.clear();
  for (const auto& force : system.forceObjects())
    if (const auto* spring = dynamic_cast<const SpringForce*>(force.get()); spring && spring->enabled())
      springs_.push_back(spring);
  gatheredStamp_ = system.structureStamp();
}

int Tearing::tear(ParticleSystem& system) {
  tornLastStep_ = 0;
  if (!settings.on()) return 0;
  if (gatheredStamp_ != system.structureStamp()) gather(system);
  const Eigen::VectorXd& x = system.positions();
  breaking_.clear();
  for (const SpringForce* spring : springs_)
    if (spring->strain(x) > settings.strain) breaking_.push_back({spring->first(), spring->second()});
  if (breaking_.empty()) return 0;
  system.breakLinks(breaking_);
  tornLastStep_ = static_cast<int>(breaking_.size());
  return tornLastStep_;
}

}  // namespace particles
