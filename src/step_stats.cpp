#include "particles/step_stats.h"

#include <algorithm>

namespace particles {

const char* stepFailureName(StepFailure failure) {
  switch (failure) {
    case StepFailure::None: return "none";
    case StepFailure::StepBelowFloor: return "step-below-floor";
    case StepFailure::WorkCapReached: return "work-cap";
    case StepFailure::SolveFailed: return "solve-failed";
    case StepFailure::ContactCapReached: return "contact-cap";
  }
  return "unknown";
}

StepStats& StepStats::operator+=(const StepStats& other) {
  solves += other.solves;
  cgIterations += other.cgIterations;
  // NaN never wins std::max against a number; a NaN residual is a failed solve, reported there.
  maxResidual = std::max(maxResidual, other.maxResidual);
  factorizations += other.factorizations;
  forceEvaluations += other.forceEvaluations;
  internalSteps += other.internalSteps;
  rejectedSteps += other.rejectedSteps;
  contactIterations += other.contactIterations;
  contactResidual = std::max(contactResidual, other.contactResidual);
  directFallbacks += other.directFallbacks;
  sleeping = std::max(sleeping, other.sleeping);
  threads = std::max(threads, other.threads);
  if (failure == StepFailure::None) failure = other.failure;
  return *this;
}

}  // namespace particles
