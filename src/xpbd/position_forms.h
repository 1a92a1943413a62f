#pragma once
// How a system's forces enter an XPBD substep (integrators/xpbd.h): stiff
// springs as compliant constraints, faces as one-sided area constraints, the
// mouse joint as a compliant attachment; every other force applied in the
// prediction. Which force takes which form is its type's row in
// forces/force_kinds.cpp.
#include <vector>

#include "particles/force.h"
#include "xpbd/angle.h"
#include "xpbd/area.h"
#include "xpbd/distance.h"

namespace particles {

class MouseSpringForce;

struct PositionForms {
  std::vector<CompliantDistance> distances;
  std::vector<CompliantAngle> angles;
  std::vector<CompliantArea> areas;  // one per face of each face-area force
  // Mouse joints, read at each projection (the target moves between steps).
  std::vector<const MouseSpringForce*> attachments;
  std::vector<const Force*> applied;  // applied as forces in the prediction
};

}  // namespace particles
