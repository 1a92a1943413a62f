#include "particles/solver_names.h"

namespace particles {

namespace {

template <class Value>
const char* lookUpName(const std::vector<ChoiceName<Value>>& table, Value value) {
  for (const auto& entry : table)
    if (entry.value == value) return entry.name;
  return "?";
}

template <class Value>
std::optional<Value> lookUpValue(const std::vector<ChoiceName<Value>>& table, const std::string& name) {
  for (const auto& entry : table)
    if (name == entry.name) return entry.value;
  return std::nullopt;
}

template <class Value>
std::string listNames(const std::vector<ChoiceName<Value>>& table) {
  std::string out;
  for (std::size_t k = 0; k < table.size(); ++k) {
    if (k > 0) out += k + 1 == table.size() ? " or " : ", ";
    out += std::string("\"") + table[k].name + "\"";
  }
  return out;
}

}  // namespace

const std::vector<ChoiceName<SolveMethod>>& solveMethodNames() {
  static const std::vector<ChoiceName<SolveMethod>> table = {
      {SolveMethod::Direct, "direct"},
      {SolveMethod::ConjugateGradient, "cg"},
  };
  return table;
}

const std::vector<ChoiceName<Preconditioner>>& preconditionerNames() {
  static const std::vector<ChoiceName<Preconditioner>> table = {
      {Preconditioner::None, "none"},
      {Preconditioner::Jacobi, "jacobi"},
      {Preconditioner::IncompleteCholesky, "incomplete-cholesky"},
  };
  return table;
}

const char* nameOf(SolveMethod method) { return lookUpName(solveMethodNames(), method); }
const char* nameOf(Preconditioner preconditioner) { return lookUpName(preconditionerNames(), preconditioner); }

std::optional<SolveMethod> solveMethodNamed(const std::string& name) { return lookUpValue(solveMethodNames(), name); }
std::optional<Preconditioner> preconditionerNamed(const std::string& name) {
  return lookUpValue(preconditionerNames(), name);
}

std::string validSolveMethodNames() { return listNames(solveMethodNames()); }
std::string validPreconditionerNames() { return listNames(preconditionerNames()); }

}  // namespace particles
