#pragma once
// The names of the constraint solve's choices, defined once: scene files and
// messages use `name` (the demo's panel has its own labels for people).
#include <optional>
#include <string>
#include <vector>

#include "particles/constraint_solver.h"

namespace particles {

template <class Value>
struct ChoiceName {
  Value value;
  const char* name;  // in scene files: "direct", "cg"; "none", "jacobi", "incomplete-cholesky"
};

const std::vector<ChoiceName<SolveMethod>>& solveMethodNames();
const std::vector<ChoiceName<Preconditioner>>& preconditionerNames();

// The name of a value (nullptr never: every enumerator is in its table).
const char* nameOf(SolveMethod method);
const char* nameOf(Preconditioner preconditioner);

// The value of a name, or nothing for an unknown one.
std::optional<SolveMethod> solveMethodNamed(const std::string& name);
std::optional<Preconditioner> preconditionerNamed(const std::string& name);

// "\"direct\" or \"cg\"" — the valid names, for messages.
std::string validSolveMethodNames();
std::string validPreconditionerNames();

}  // namespace particles
