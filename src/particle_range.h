#pragma once
// The engine's threading callbacks: a pass that runs over ranges of particles
// once their entries are final, fused into the force pass that makes them
// (ForceBatches::applyAndDivide, the explicit schemes' stages, xpbd's passes).
#include <functional>

namespace particles {

// A pass over the particles [begin, end) (entries [2 begin, 2 end) of a 2n
// vector), called over ranges that cover every particle, on several threads
// at once when the caller runs in parallel.
using ParticleRange = std::function<void(int begin, int end)>;
// The same pass in the k-th of a sequence of evaluations (an integrator's
// stages): particles [begin, end) of evaluation `stage`.
using StageRange = std::function<void(int stage, int begin, int end)>;
// Evaluation `stage`'s pass of then as a ParticleRange (empty when then is;
// it refers to then, which must outlive it).
inline ParticleRange stagePass(const StageRange& then, int stage) {
  if (!then) return {};
  return [&then, stage](int begin, int end) { then(stage, begin, end); };
}

}  // namespace particles
