#pragma once
// The built-in force types' ways into the engine's fast paths, one row per
// type in force_kinds.cpp: how a force joins the force batches of an
// evaluation (forces/force_batch.h) and which position form it takes in an
// XPBD substep (xpbd/position_forms.h). A type without a row, or a row
// without an entry for a path (wind, a gas's pressure, a user's own force
// type), is evaluated through its virtual apply there. Adding a force type
// is its header and source, and a row here if it has a fast path (the
// scene file's codecs and the demo's colours have one row per type too).
#include <vector>

#include "particles/force.h"

namespace particles {

class SpringBatch;
struct FieldTerm;
struct PositionForms;

// How a force joined the batches.
enum class Batched { No, Springs, Field };

struct ForceKind {
  const char* type;  // Force::type()
  // Adds the force to the open spring batch, or sets the field term; No:
  // not this type's class after all (a user's force of the same name), or
  // no batch.
  Batched (*batch)(const Force& force, SpringBatch& springs, FieldTerm& field);
  // Adds the force's position form for substeps of h (none for a torn
  // spring) and returns true, or returns false: the force is applied in the
  // prediction (as every force of a type whose entry is null).
  bool (*positionForm)(const Force& force, double h, PositionForms& forms);
};

// The row of force.type(), or nullptr.
const ForceKind* forceKind(const Force& force);
// Every row.
const std::vector<ForceKind>& forceKinds();

}  // namespace particles
