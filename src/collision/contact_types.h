#pragma once
// What every phase of the contact pass reads and returns: the step's start
// and the count of what a pass did.
#include <Eigen/Core>

#include "particles/collision.h"

namespace particles {

// The state at the start of the step, from which continuous detection sweeps.
// Each particle's path through the step runs from (x, v) here to its state as
// the integrator left it (contact_path.h); every contact pass reads it before
// any contact has changed that particle.
struct StepStart {
  const Eigen::VectorXd& x;  // 2n positions
  const Eigen::VectorXd& v;  // 2n velocities
  double dt;
  const PathBounds* paths = nullptr;  // the paths' box (x here → the present), when the caller has it
};

// What one contact pass did: the contacts it resolved and the particles that
// ran out of the work cap ContactSettings::maxImpacts (nonzero fails the step).
struct ContactCount {
  int contacts = 0;
  int capped = 0;
  ContactCount& operator+=(const ContactCount& other) {
    contacts += other.contacts;
    capped += other.capped;
    return *this;
  }
};

}  // namespace particles
