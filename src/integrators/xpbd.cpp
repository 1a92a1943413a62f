#include "integrators/xpbd.h"

#include <algorithm>
#include <cstdint>
#include <mutex>

#include "forces/force_kinds.h"
#include "parallel_for.h"
#include "particles/cancel.h"
#include "particles/forces/mouse_spring.h"
#include "particles/particle_system.h"
#include "particles/threads.h"
#include "xpbd/constraint_projection.h"
#include "vector_kernels.h"

namespace particles {

namespace {

constexpr int kPassBlock = 512;  // particles a per-particle pass takes at a time (f and a: 8 KB each)

// v ← v + h a, xⁿ ← x, x ← x + h v over `count` entries.
PARTICLES_VECTOR_CLONES void advanceEntries(int count, double h, const double* a, double* v, double* x, double* xn) {
#pragma omp simd
  for (int k = 0; k < count; ++k) {
    v[k] += h * a[k];
    xn[k] = x[k];
    x[k] += h * v[k];
  }
}

// v ← (x − xⁿ)/h over the entries [begin, end).
PARTICLES_VECTOR_CLONES void velocitiesFromPositions(int begin, int end, double h, const double* x, const double* xn,
                                                     double* v) {
#pragma omp simd
  for (int k = begin; k < end; ++k) v[k] = (x[k] - xn[k]) / h;
}

}  // namespace

XpbdIntegrator::Forms XpbdIntegrator::positionForms(const ParticleSystem& system, double h) {
  Forms forms;
  for (const auto& force : system.forceObjects()) {
    const ForceKind* kind = forceKind(*force);
    if (!kind || !kind->positionForm || !kind->positionForm(*force, h, forms)) forms.applied.push_back(force.get());
  }
  return forms;
}

void XpbdIntegrator::configure(const IntegratorSettings& settings) {
  settings.validate();
  if (settings.xpbd.lines != settings_.lines) preparedStamp_ = 0;  // the lines are part of the forms
  settings_ = settings.xpbd;
}

StepStats XpbdIntegrator::step(ParticleSystem& system, double dt) {

  const double h = dt / settings_.substeps;
  prepare(system, h);
  // With fields alone and no hanging lines, each block of particles is
  // predicted just before its springs are first projected, on the thread
  // that projects them (DistanceBlocks::project's `before`).
  const bool fused = applied_.fieldsOnly() && lines_.lines() == 0;
  // The last pass updates the velocities range by range (project()'s
  // thenVelocities); each range's part of the paths' box is merged into the
  // substep's under a lock (minima and maxima: the same in any order).
  PathBounds paths;
  std::mutex merging;
  const ParticleRange predictRange = [&](int begin, int end) { predictFields(system, h, begin, end); };
  const ParticleRange velocityRange = [&](int begin, int end) {
    const PathBounds part = updateVelocities(system, h, begin, end);
    const std::lock_guard<std::mutex> lock(merging);
    paths.merge(part);
  };
  // Up to 100,000 substeps of 10,000 passes each: the cancel flag is watched
  // before every substep and every pass (particles/cancel.h); a step cut
  // short leaves the state mid-substep, for the caller to discard.
  for (int k = 0; k < settings_.substeps && !cancelRequested(); ++k) {
    beginSubstep(system);
    if (!fused) predict(system, h);
    paths = PathBounds{};
    int pass = 0;
    for (; pass < settings_.iterations && !cancelRequested(); ++pass)
      project(system, pass, fused && pass == 0 ? predictRange : ParticleRange(),
              pass + 1 == settings_.iterations ? velocityRange : ParticleRange());
    if (pass < settings_.iterations) break;
    collide(system, h, paths);
  }
  lastStep_ = h;
  // The constraint passes are Gauss–Seidel sweeps, not linear solves: solves
  // and CG iterations stay 0; the forces without a position form are applied
  // once per substep.
  StepStats stats;
  stats.internalSteps = settings_.substeps;
  stats.forceEvaluations = settings_.substeps;
  return stats;
}

// The position forms depend on the structure (forces, constraints, pins) and
// on h alone, so they are rebuilt only when either changes.
void XpbdIntegrator::prepare(const ParticleSystem& system, double h) {
  if (system.structureStamp() == preparedStamp_ && h == preparedStep_) return;
  preparedStamp_ = 0;  // a refusal below leaves nothing prepared
  forms_ = positionForms(system, h);
  if (settings_.lines) {
    distances_.build(lines_.build(forms_.distances, system.constraints(), system.phase()), system.inverseMasses());
  } else {
    lines_.clear();
    distances_.build(forms_.distances, system.inverseMasses());
  }
  applied_.update(forms_.applied, ++appliedStamp_);
  angleLambda_.resize(forms_.angles.size());
  attachmentLambda_.resize(forms_.attachments.size());
  areaLambda_.resize(forms_.areas.size());
  preparedStamp_ = system.structureStamp();
  preparedStep_ = h;
}

// xⁿ (and vⁿ) sized; the multipliers restart at 0.
void XpbdIntegrator::beginSubstep(const ParticleSystem& system) {
  const int n = system.size();
  xn_.resize(2 * n);
  if (system.colliding()) vn_.resize(2 * n);
  std::fill(angleLambda_.begin(), angleLambda_.end(), 0.0);
  std::fill(areaLambda_.begin(), areaLambda_.end(), 0.0);
  std::fill(attachmentLambda_.begin(), attachmentLambda_.end(), Eigen::Vector2d::Zero());
}

// f = Σ of the forces without a position form at the substep's start and
// a = W f (force batches: fields and springs of zero stiffness as flat
// arrays), then v ← v + h a, xⁿ ← x, x ← x + h v (vⁿ ← v before, for the
// contacts). When the forces are fields alone, range by range.
void XpbdIntegrator::predict(ParticleSystem& system, double h) {
  const int n = system.size();
  if (applied_.fieldsOnly()) {
    parallelRanges(n, threadCount(), kParallelParticles,
                   [&](int begin, int end) { predictFields(system, h, begin, end); });
    return;
  }
  applied_.applyAndDivide(system.phase(), force_, acceleration_);
  parallelRanges(n, threadCount(), kParallelParticles,
                 [&](int begin, int end) { advance(system, h, begin, end, acceleration_.data() + 2 * begin); });
}

// The prediction of particles [begin, end) when the forces are fields alone:
// block by block, f and a in a block's scratch on the stack, so that they
// never reach memory.
void XpbdIntegrator::predictFields(ParticleSystem& system, double h, int begin, int end) {
  const Phase s = system.phase();
  alignas(64) double f[2 * kPassBlock], a[2 * kPassBlock];
  for (int block = begin; block < end; block += kPassBlock) {
    const int blockEnd = std::min(end, block + kPassBlock);
    applied_.applyAndDivide(block, blockEnd, s, f, a);
    advance(system, h, block, blockEnd, a);
  }
}

// v ← v + h a, xⁿ ← x, x ← x + h v on particles [begin, end) (vⁿ ← v first
// when colliding), a from the range's first entry.
void XpbdIntegrator::advance(ParticleSystem& system, double h, int begin, int end, const double* a) {
  double* x = positionsOf(system).data() + 2 * begin;
  double* v = velocitiesOf(system).data() + 2 * begin;
  if (system.colliding()) std::copy(v, v + 2 * (end - begin), vn_.data() + 2 * begin);
  advanceEntries(2 * (end - begin), h, a, v, x, xn_.data() + 2 * begin);
}

// One Gauss–Seidel pass: the hanging lines (with XpbdSettings::lines), the
// other compliant springs in colour order, block by block (xpbd/distance_blocks.h,
// which runs predictFirst, when given, on each block first), angle springs,
// then the hard constraints, so that those hold as well as one pass can make them.
// thenVelocities, when given, runs on every particle once the pass is done:
// when the springs are the pass's last projection, inside their parallel
// region, on each block once its springs are done, on the thread that
// projected them (DistanceBlocks::project's after); otherwise at the end.
void XpbdIntegrator::project(ParticleSystem& system, int pass, const ParticleRange& predictFirst,
                             const ParticleRange& thenVelocities) {
  Eigen::VectorXd& x = positionsOf(system);
  const Eigen::VectorXd& w = system.inverseMasses();
  const bool springsLast = forms_.angles.empty() && forms_.areas.empty() && forms_.attachments.empty() &&
                           system.constraints().empty();
  if (lines_.lines() > 0) lines_.project(xn_, x, velocitiesOf(system), system.masses(), w, pass);
  distances_.project(xn_.data(), x.data(), pass, settings_.iterations, predictFirst,
                     springsLast ? thenVelocities : ParticleRange());
  for (std::size_t k = 0; k < forms_.angles.size(); ++k)
    projectAngle(forms_.angles[k], w, xn_, x, angleLambda_[k]);
  for (std::size_t k = 0; k < forms_.areas.size(); ++k) projectArea(forms_.areas[k], w, x, areaLambda_[k]);
  for (std::size_t k = 0; k < forms_.attachments.size(); ++k) {
    const MouseSpringForce& mouse = *forms_.attachments[k];
    const CompliantAttachment c{mouse.particle(), mouse.target(),
                                springCompliance(mouse.stiffness(), mouse.damping(), preparedStep_)};
    projectAttachment(c, w, xn_, x, attachmentLambda_[k]);
  }
  for (const auto& constraint : system.constraints())
    projectConstraint(*constraint, velocitiesOf(system), system.masses(), w, x, blocks_);
  if (thenVelocities && !springsLast) parallelRanges(system.size(), threadCount(), kParallelParticles, thenVelocities);
}

// Contacts over the substep, from (xⁿ, vⁿ) to the projected state.
void XpbdIntegrator::collide(ParticleSystem& system, double h, const PathBounds& paths) {
  if (system.colliding()) system.collideOver(xn_, vn_, h, &paths);
}

// v ← (x − xⁿ)/h on particles [begin, end), block by block; pinned particles
// (w = 0) never moved and keep v = 0. When the scene collides, the same loop
// measures the box of their paths for the contact pass.
PathBounds XpbdIntegrator::updateVelocities(ParticleSystem& system, double h, int begin, int end) {
  const double* x = positionsOf(system).data();
  const double* xn = xn_.data();
  double* v = velocitiesOf(system).data();
  const double* radius = system.radii().data();
  const bool colliding = system.colliding();
  PathBounds paths;
  for (int block = begin; block < end; block += kPassBlock) {
    const int blockEnd = std::min(end, block + kPassBlock);
    velocitiesFromPositions(2 * block, 2 * blockEnd, h, x, xn, v);
    if (colliding) paths.merge(PathBounds::of(xn, x, radius, block, blockEnd));
  }
  return paths;
}

}  // namespace particles
