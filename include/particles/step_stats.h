#pragma once
// What one step did, with one meaning for every integrator and every tool:
// returned by Integrator::step and ParticleSystem::step, read by the runner's
// CSV, the laboratory and the demo's HUD.
namespace particles {

// Why a step could not be completed as asked. The state after a failed step
// is finite but not the one the step was meant to reach; the tools treat a
// failure as a divergence (DivergenceReason::StepFailed).
enum class StepFailure {
  None,
  StepBelowFloor,  // an adaptive scheme needed an internal step below its floor
  WorkCapReached,  // an adaptive scheme ran out of its work budget for one call
  SolveFailed,     // a linear solve gave non-finite multipliers or residual
  ContactCapReached,  // a particle needed more impacts in one step than ContactSettings::maxImpacts,
                      // or the discs more pairs than a step takes on (64 a disc, at least 2^20)
};

// One-word name of a failure ("none", "step-below-floor", "work-cap", "solve-failed", "contact-cap").
const char* stepFailureName(StepFailure failure);

struct StepStats {
  int solves = 0;            // linear solves (constraint solves, implicit Newton passes)
  int cgIterations = 0;      // CG iterations summed over every solve of the step
  double maxResidual = 0.0;  // largest relative residual |r|/|b| of any solve in the step
  int factorizations = 0;    // numeric factorisations (LDLᵀ, incomplete Cholesky)
  int forceEvaluations = 0;  // evaluations of the force accumulator Q (every force applied once)
  int internalSteps = 1;     // accepted internal steps (1 for fixed-step schemes)
  int rejectedSteps = 0;     // internal steps rejected by an error controller
  int contactIterations = 0;     // sweeps of the coupled contact–constraint solve, summed
  double contactResidual = 0.0;  // largest velocity change (m/s) in the last sweep of any coupled solve
  int directFallbacks = 0;       // constraint solves asked of CG and solved directly (SolverSettings::maxCgWork)
  int sleeping = 0;              // particles asleep at the step's end (islands at rest: src/collision/islands.h)
  int threads = 1;  // threads the step's parallel loops ran on (ParticleSystem::step's choice,
                    // src/thread_use.h; 1 when the step entered no parallel region)
  StepFailure failure = StepFailure::None;  // the first failure, if any

  // Sums the counts, keeps the largest residual, the most sleeping, the most
  // threads and the first failure: the statistics of two steps (or two parts
  // of one) taken one after the other.
  StepStats& operator+=(const StepStats& other);
};

}  // namespace particles
