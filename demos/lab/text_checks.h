#pragma once
// Sentences of the report held against the data they describe. A sentence
// that compares (X is cheaper, Y grows with dt, never Z) is either generated
// from the data ({{value:...}}, {{table:...}}) or carries a check that
// render-report evaluates on every rendering and every --check:
//
//   {{check:never FILE COND...}}            no row of DATA/FILE meets every COND
//   {{check:some FILE COND...}}             at least one row meets every COND
//   {{check:every FILE A OP B [COND...]}}   every row meeting the CONDs has A OP B
//   {{check:increasing FILE X Y [COND...]}} over the rows meeting the CONDs,
//   {{check:decreasing FILE X Y [COND...]}}   ordered by X, Y strictly rises (falls)
//   {{check:value KEY OP B}}                the value recorded under KEY (values.csv)
//
// FILE is a CSV of the data directory with a header row; A, X, Y are its
// columns; B is a column (a key for `value`) or a number; OP is one of
// < <= > >= = !=; COND is COLUMN OP VALUE without spaces (integrator=euler,
// budget_relative<0.001, survived_dt<smallest_failure_dt; VALUE may name a
// column): numbers compare as numbers, other text as text. For `value`, B
// may carry a factor: 3*stability.survived_dt.euler.cl6.
// A check renders as nothing.
//
// Besides the declared checks two rules read the prose itself:
//   - "never X", X an integrator (by its name or as the report writes it:
//     explicit Euler, symplectic Euler, RK4 ...), contradicts data in which
//     the cost experiment names X as the cheapest pick (cost_vs_size.csv, and
//     the rows of cost_of_accuracy.csv marked cheapest);
//   - a step called safe ("safe dt", "safe step", "certified dt", "certified
//     safe") claims it never fails, which no finite set of runs shows: the
//     sentence (or table line) must state the bound its runs support ("p ≤").
#include <stdexcept>
#include <string>
#include <vector>

namespace lab {

// Every contradiction found in one rendering, one line each.
struct ReportContradiction : std::runtime_error {
  explicit ReportContradiction(const std::vector<std::string>& found);
  std::vector<std::string> found;
};

// "" when the check (the text after "check:") holds against dataDir, else
// why not, naming the row that breaks it. Throws std::runtime_error for a
// malformed check or a file or column that does not exist.
std::string evaluateCheck(const std::string& check, const std::string& dataDir);

// The prose rules above over `text` (Markdown; emphasis is ignored): one line
// per "never X" that the data contradicts and per step called safe without its bound.
std::vector<std::string> proseContradictions(const std::string& text, const std::string& dataDir);

}  // namespace lab
