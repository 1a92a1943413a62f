#pragma once
// What a run writes per step, shared by the subcommands that step scenes:
// the divergence test and the CSV rows of --csv and --trajectory.
#include <ostream>

#include "particles/particle_system.h"

namespace cli {

// A position or velocity is non-finite, or so large that its square
// overflows (the energies and constraint errors are then infinite): an
// exploded state can grow for many steps before it turns into inf and NaN.
bool diverged(const particles::ParticleSystem& s);

constexpr const char* kDiagnosticsHeader =
    "step,t,kinetic,potential,total_energy,max_constraint_error,cg_iterations,cg_residual,step_us";
// One diagnostics row for the state after `step`; stepMicros is that step's wall time.
void writeDiagnostics(std::ostream& out, long long step, const particles::ParticleSystem& s, double stepMicros);

constexpr const char* kTrajectoryHeader = "step,t,particle,x,y,vx,vy";
// One trajectory row per particle.
void writeTrajectory(std::ostream& out, long long step, const particles::ParticleSystem& s);

}  // namespace cli
