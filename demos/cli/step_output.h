#pragma once
// What a run writes per step, shared by the subcommands that step scenes:
// the runner's divergence limits and the CSV rows of --csv and --trajectory.
#include <string>
#include <vector>

#include "output/csv_writer.h"
#include "scene.h"

#include "particles/divergence.h"
#include "particles/particle_system.h"

namespace cli {

// The runner stops at a non-finite state (a position, velocity or energy
// that is not finite, or |q|², |v|² overflowing: an exploded state grows for
// many steps before it turns into inf and NaN), at a failed step (a solve
// with non-finite multipliers, an adaptive step below its floor or over its
// work cap, a particle over the contact work cap) and at an energy blow-up:
//   E − E₀ > kEnergyBoundFactor · E_ref,
// E_ref = particles::blowUpEnergyScale(system, L) of the state the run starts
// from, L = sceneLength(); and at a constraint solve whose relative residual
// passes kMaxSolveResidual (CG that cannot converge on a contradictory
// constraint set: the damped direct solve's least-squares answer on the
// taut chain leaves 0.45). Constraint error is recorded, not judged.
// The factor leaves every built-in scene at its own integrator and dt far
// inside the bound (the largest rise over 3 s is 1.5e-4 E_ref, the test
// chain's under RK4; test RunnerDivergence.BuiltInScenesStayInsideTheEnergyBoundAtTheirDefaults
// prints each), and the scenes under the other schemes inside it unless they
// blow up (explicit Euler on the cloth, hair, chains and rope; Verlet on the
// rod chains at dt 0.002 — each by 10³ to 10²⁰ J when stopped), while an
// unstable scheme, which multiplies the energy step after step, crosses it
// long before its state overflows.
constexpr double kEnergyBoundFactor = 100.0;
constexpr double kMaxSolveResidual = 10.0;
particles::DivergenceLimits runnerDivergenceLimits(particles::ParticleSystem& system, double sceneLength);

// L of the energy bound: the diagonal of the box around the scene's view and
// its initial positions (a scene of one particle still has the size it is shown at).
double sceneLength(const scenes::Scene& scene);

// The columns after max_constraint_error come from the step's StepStats:
// cg_iterations summed over every solve of the step, cg_residual the largest
// relative residual of any of them, solves, force_evaluations and
// internal_steps (accepted steps of an adaptive scheme; 1 otherwise); then
// the step's wall time, the threads it ran on (StepStats::threads), the
// contacts its contact pass resolved and the particles asleep at its end.
inline const std::vector<std::string> kDiagnosticsColumns = {
    "step",          "t",           "kinetic", "potential",         "total_energy",   "max_constraint_error",
    "cg_iterations", "cg_residual", "solves",  "force_evaluations", "internal_steps", "step_us",
    "threads",       "contacts",    "sleeping"};
// The measured columns of one row, evaluated once per step (the energies
// and the constraint error each cost a pass over the forces or constraints).
struct Diagnostics {
  long long step = 0;
  double time = 0.0, kinetic = 0.0, potential = 0.0, constraintError = 0.0;
  particles::StepStats stats;  // the step's statistics (zeros for row 0)
  int contacts = 0;            // contacts the step's contact pass resolved
};
// The state after `step`, its statistics from s.lastStepStats().
Diagnostics measureDiagnostics(long long step, const particles::ParticleSystem& s);

// The first CSV column of a row that is not finite, as a phrase for the
// divergence message ("the kinetic energy is not finite"); empty when all
// are. The CSV only ever holds finite numbers: the runner ends a run whose
// diagnostics are not finite as a divergence, after
// particles::checkDivergence (which judges the state and the step).
std::string nonFiniteDiagnostics(const Diagnostics& d);

// One diagnostics row; stepMicros is that step's wall time.
void writeDiagnostics(output::CsvWriter& csv, const Diagnostics& d, double stepMicros);

inline const std::vector<std::string> kTrajectoryColumns = {"step", "t", "particle", "x", "y", "vx", "vy"};
// One trajectory row per particle.
void writeTrajectory(output::CsvWriter& csv, long long step, const particles::ParticleSystem& s);

}  // namespace cli
