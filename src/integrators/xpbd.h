#pragma once
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "particles/collision.h"
#include "particles/force.h"
#include "forces/force_batch.h"
#include "particles/integrator.h"
#include "xpbd/angle.h"
#include "xpbd/area.h"
#include "xpbd/attachment.h"
#include "xpbd/distance_blocks.h"
#include "xpbd/hanging_lines.h"
#include "xpbd/position_forms.h"

namespace particles {

class Constraint;
class MouseSpringForce;

// Extended position-based dynamics with small steps (Macklin, Müller &
// Chentanez 2016; Macklin et al. 2019, "Small Steps in Physics Simulation").
// A step of dt takes `substeps` substeps (XpbdSettings) of h = dt/substeps; each one
//   applies the forces without a position form (gravity, drag, wind, springs
//     of zero stiffness) at (x, v):   v ← v + h W f,  xⁿ ← x,  x ← x + h v;
//   projects, `iterations` times in Gauss–Seidel order, the damped springs as
//     compliant distance constraints (α = 1/k_s, β = k_d; with
//     XpbdSettings::lines first the lines hanging from held particles, each
//     solved directly, xpbd/hanging_lines.h; then xpbd/distance.h, in
//     colour order, block by block of particles, xpbd/distance_blocks.h), the
//     angle springs as compliant angle constraints (xpbd/angle.h), the faces
//     of a face-area force as one-sided area constraints (xpbd/area.h), the mouse
//     joint as a compliant attachment to its target (xpbd/attachment.h), then
//     the rods, wires and lines as hard constraints through their C and J kernels
//     (xpbd/constraint_projection.h), the multipliers λ starting at 0;
//   sets v ← (x − xⁿ)/h;
//   resolves contacts over the substep (ParticleSystem::collideOver, swept
//     along each particle's path from xⁿ), so that a contact's impulse enters
//     the next substep's prediction and constraints.
// The position error is first order in h. A force without a position form in
// the table in forces/force_kinds.cpp (fields, drag, wind, pressure, a user's own force type) is
// applied in the prediction, explicitly, once per substep. Torn springs and
// angle springs have no form at all.
class XpbdIntegrator : public Integrator {
 public:
  const char* name() const override { return "xpbd"; }
  bool collidesInSubsteps() const override { return true; }
  // The mouse joint is projected as a compliant attachment, stable at any stiffness.
  StepStats step(ParticleSystem& system, double dt) override;
  // Takes IntegratorSettings::xpbd (validated first).
  void configure(const IntegratorSettings& settings) override;
  const XpbdSettings& settings() const { return settings_; }

  // How every force of the system enters a substep of h, compliances set for
  // that h (each force by its type's row in forces/force_kinds.cpp).
  using Forms = PositionForms;
  static Forms positionForms(const ParticleSystem& system, double h);

 private:
  void prepare(const ParticleSystem& system, double h);
  void beginSubstep(const ParticleSystem& system);
  void predict(ParticleSystem& system, double h);
  void predictFields(ParticleSystem& system, double h, int begin, int end);
  void advance(ParticleSystem& system, double h, int begin, int end, const double* a);
  void collide(ParticleSystem& system, double h, const PathBounds& paths);
  void project(ParticleSystem& system, int pass, const ParticleRange& predictFirst,
               const ParticleRange& thenVelocities);
  PathBounds updateVelocities(ParticleSystem& system, double h, int begin, int end);

  XpbdSettings settings_;
  Forms forms_;
  std::uint64_t preparedStamp_ = 0;  // ParticleSystem::structureStamp() forms_ was built for
  double preparedStep_ = 0.0;        // and the substep h
  HangingLines lines_;               // with XpbdSettings::lines
  DistanceBlocks distances_;         // the springs on no line
  std::vector<double> angleLambda_;
  std::vector<double> areaLambda_;
  std::vector<Eigen::Vector2d> attachmentLambda_;
  std::vector<Eigen::Vector2d> blocks_;
  ForceBatches applied_;             // forms_.applied as batches
  std::uint64_t appliedStamp_ = 0;   // applied_ rebuilt at each prepare()
  Eigen::VectorXd force_, acceleration_, xn_, vn_;  // f, W f; x and v at the substep's start
};

}  // namespace particles
