#include "divergence_words.h"

#include <fmt/format.h>

namespace demo {

namespace {
using particles::DivergenceReason;
using particles::StepFailure;

// One entry per reason (and, for a failed step, per failure); the first
// that matches says it.
struct Words {
  DivergenceReason reason;
  StepFailure failure;  // StepFailure::None: any
  const char* brief;
  const char* text;
};
constexpr Words kWords[] = {
    {DivergenceReason::NonFinite, StepFailure::None, "the numbers blew up",
     "the numbers blew up to infinity: the step is too long for this integrator on the scene's fastest motion"},
    {DivergenceReason::StepFailed, StepFailure::ContactCapReached, "a particle struck the walls too often",
     "a particle struck the walls more often in one step than the contact pass follows: it moves too fast for this "
     "step (the integrator gained energy)"},
    {DivergenceReason::StepFailed, StepFailure::StepBelowFloor, "the adaptive step fell below its floor",
     "the adaptive integrator needed a step shorter than its floor: the motion is too stiff for its tolerance"},
    {DivergenceReason::StepFailed, StepFailure::WorkCapReached, "the adaptive step ran out of work",
     "the adaptive integrator ran out of its work for one step: the scene is too stiff for it"},
    {DivergenceReason::StepFailed, StepFailure::SolveFailed, "a constraint solve failed",
     "a constraint solve gave no finite answer: the constraints contradict each other or the step is too long"},
    {DivergenceReason::StepFailed, StepFailure::None, "the step failed", "the step could not be completed"},
    {DivergenceReason::SolveFailed, StepFailure::None, "a constraint solve did not converge",
     "a constraint solve did not converge: the constraints pull against each other"},
    {DivergenceReason::ConstraintViolation, StepFailure::None, "a constraint drifted off",
     "a constraint drifted off by more than its own size: the step is too long for this integrator"},
    {DivergenceReason::EnergyGrowth, StepFailure::None, "the energy grew without bound", "the energy grew without bound: the integrator adds energy at this step"},
    {DivergenceReason::OutOfBounds, StepFailure::None, "a particle was flung away", "a particle was flung far out of the scene"},
};
}  // namespace

std::string divergenceInWords(const particles::Divergence& d, bool brief) {
  for (const Words& w : kWords)
    if (w.reason == d.reason && (w.failure == StepFailure::None || w.failure == d.failure)) return brief ? w.brief : w.text;
  return d.message();
}

}  // namespace demo
