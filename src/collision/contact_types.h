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

// Where each particle's path over the rest of the step starts: the step's
// start, or its last impact (at time dt − h). The narrow phase sweeps from
// there, and the solve moves a particle it holds to x + h v (v its solved
// velocity at the step's end).
struct References {
  Eigen::VectorXd x, v;  // 2n
  Eigen::VectorXd h;     // n: time from the reference to the step's end

  void reset(const StepStart& start);
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
