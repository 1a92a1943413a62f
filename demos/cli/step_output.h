#pragma once
// What a run writes per step, shared by the subcommands that step scenes:
// the divergence test and the CSV rows of --csv and --trajectory.
#include <ostream>
#include <string>

#include "particles/particle_system.h"

namespace cli {

// A position or velocity is non-finite, or so large that its square
// overflows (the energies and constraint errors are then infinite): an
// exploded state can grow for many steps before it turns into inf and NaN.
bool diverged(const particles::ParticleSystem& s);

// The per-step diagnostics of a state, as the CSV shows them.
struct Diagnostics {
  double time = 0.0;
  double kinetic = 0.0, potential = 0.0;
  double maxConstraintError = 0.0;
  int cgIterations = 0;
  double cgResidual = 0.0;  // of the last constraint solve
};
Diagnostics measure(const particles::ParticleSystem& s);

// The first diagnostic that is not finite, as a phrase for the divergence
// message ("the kinetic energy is not finite"); empty when all are finite.
// The CSV only ever holds finite numbers: a step whose diagnostics are not
// finite ends the run as a divergence.
std::string nonFinite(const Diagnostics& d);

constexpr const char* kDiagnosticsHeader =
    "step,t,kinetic,potential,total_energy,max_constraint_error,cg_iterations,cg_residual,step_us";
// One diagnostics row for the state after `step`; stepMicros is that step's wall time.
void writeDiagnostics(std::ostream& out, long long step, const Diagnostics& d, double stepMicros);

constexpr const char* kTrajectoryHeader = "step,t,particle,x,y,vx,vy";
// One trajectory row per particle.
void writeTrajectory(std::ostream& out, long long step, const particles::ParticleSystem& s);

}  // namespace cli
