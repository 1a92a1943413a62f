#include "forces/force_kinds.h"

#include <cstring>

#include "forces/force_batch.h"
#include "forces/spring_batch.h"
#include "particles/forces/angular_spring.h"
#include "particles/forces/drag.h"
#include "particles/forces/face_area.h"
#include "particles/forces/gravity.h"
#include "particles/forces/mouse_spring.h"
#include "particles/forces/spring.h"
#include "xpbd/multiplier.h"
#include "xpbd/position_forms.h"

namespace particles {

namespace {

Batched batchSpring(const Force& force, SpringBatch& springs, FieldTerm&) {
  const auto* spring = dynamic_cast<const SpringForce*>(&force);
  if (!spring) return Batched::No;
  if (spring->enabled())
    springs.add(spring->first(), spring->second(), spring->restLength(), spring->stiffness(), spring->damping());
  return Batched::Springs;  // a torn spring adds nothing, and keeps the spring segment open
}

Batched batchGravity(const Force& force, SpringBatch&, FieldTerm& field) {
  const auto* gravity = dynamic_cast<const GravityForce*>(&force);
  if (!gravity) return Batched::No;
  field = {FieldTerm::Kind::Gravity, gravity->acceleration(), 0.0};
  return Batched::Field;
}

Batched batchDrag(const Force& force, SpringBatch&, FieldTerm& field) {
  const auto* drag = dynamic_cast<const DragForce*>(&force);
  if (!drag) return Batched::No;
  field = {FieldTerm::Kind::Drag, Eigen::Vector2d::Zero(), drag->damping()};
  return Batched::Field;
}

// Each returns false for a force it gives no form (another class of the same
// name, or no stiffness to make a compliance of): the force is then applied.
// Compliance needs k_s > 0: a spring or angle spring of zero stiffness is a
// pure damper, applied as a force.
bool springForm(const Force& force, double h, PositionForms& forms) {
  const auto* spring = dynamic_cast<const SpringForce*>(&force);
  if (spring == nullptr) return false;
  if (!spring->enabled()) return true;  // torn: no form at all
  if (spring->stiffness() == 0.0) return false;
  CompliantDistance c;
  c.i = spring->first();
  c.j = spring->second();
  c.rest = spring->restLength();
  c.compliance = springCompliance(spring->stiffness(), spring->damping(), h);
  forms.distances.push_back(c);
  return true;
}

bool angularSpringForm(const Force& force, double h, PositionForms& forms) {
  const auto* spring = dynamic_cast<const AngularSpringForce*>(&force);
  if (spring == nullptr) return false;
  if (!spring->enabled()) return true;  // an arm torn: no form at all
  if (spring->stiffness() == 0.0) return false;
  CompliantAngle c;
  for (int n = 0; n < 3; ++n) c.p[n] = spring->triple()[n];
  c.restAngle = spring->restAngle();
  c.compliance = springCompliance(spring->stiffness(), spring->damping(), h);
  forms.angles.push_back(c);
  return true;
}

// A mouse joint of positive stiffness is held by a compliant attachment.
bool mouseSpringForm(const Force& force, double, PositionForms& forms) {
  const auto* mouse = dynamic_cast<const MouseSpringForce*>(&force);
  if (mouse == nullptr || mouse->stiffness() == 0.0) return false;
  forms.attachments.push_back(mouse);
  return true;
}

// A face-area force of positive stiffness: each face a one-sided compliant
// area constraint (xpbd/area.h); of none, no force at all.
bool faceAreaForm(const Force& force, double h, PositionForms& forms) {
  const auto* area = dynamic_cast<const FaceAreaForce*>(&force);
  if (area == nullptr) return false;
  if (area->stiffness() == 0.0) return true;
  for (const AreaFace& face : area->faces()) {
    CompliantArea c;
    c.ring = face.ring;
    c.restArea = face.restArea;
    c.floor = area->floor();
    c.compliance = springCompliance(area->stiffness() * face.restArea, 0.0, h);
    forms.areas.push_back(std::move(c));
  }
  return true;
}

}  // namespace

const std::vector<ForceKind>& forceKinds() {
  static const std::vector<ForceKind> table = {
      // type           batch         position form
      {"spring", batchSpring, springForm},
      {"gravity", batchGravity, nullptr},
      {"drag", batchDrag, nullptr},
      {"angular-spring", nullptr, angularSpringForm},
      {"mouse-spring", nullptr, mouseSpringForm},
      {"face-area", nullptr, faceAreaForm},
  };
  return table;
}

const ForceKind* forceKind(const Force& force) {
  const char* type = force.type();
  for (const ForceKind& kind : forceKinds())
    if (std::strcmp(kind.type, type) == 0) return &kind;
  return nullptr;
}

}  // namespace particles
