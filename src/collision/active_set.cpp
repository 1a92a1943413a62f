// The velocity problem of an island solved exactly by an active set (solver_rows.h).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "solver_rows.h"

namespace particles::solve {

namespace {

constexpr int kMaxIterations = 32;

enum class State : std::uint8_t { Off, Active, Sliding };

}  // namespace

Relaxed activeSetVelocities(RowSystem& R, const std::vector<int>& contactRows, const std::vector<int>& constraints,
                            const ContactSettings& settings, Eigen::VectorXd& v, bool& settled) {
  const double tolerance = settings.coupledTolerance;
  const std::size_t m = contactRows.size();
  // A row's state from its impulse so far (a warm start's guess of the set).
  std::vector<State> state(m, State::Off);
  for (std::size_t k = 0; k < m; ++k) {
    const Row& row = R.rows[contactRows[k]];
    if (row.lambda != 0.0) state[k] = State::Active;
  }
  DirectBlock block;
  std::vector<int> active;
  Relaxed solved;
  settled = false;
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    solved.passes = iteration + 1;
    bool changed = false;
    double worst = 0.0;
    // Normals that approach faster than their target join; friction follows
    // its normal (a contact list has each friction row right after it).
    for (std::size_t k = 0; k < m; ++k) {
      Row& row = R.rows[contactRows[k]];
      if (row.invK == 0.0) continue;
      const double error = row.target - R.velocityOf(row, v);
      if (row.kind == RowKind::Normal) {
        if (state[k] == State::Off && error > tolerance) state[k] = State::Active, changed = true;
        worst = std::max(worst, state[k] == State::Active ? std::abs(error) : std::max(0.0, error));
        continue;
      }
      if (state[k - 1] != State::Active) {  // its normal lets go: so does it
        if (row.lambda != 0.0) R.move(row, -row.lambda, v), row.lambda = 0.0, changed = true;
        state[k] = State::Off;
        continue;
      }
      if (state[k] == State::Off) state[k] = State::Active, changed = true;
      // Sliding, and the velocity it resists turned round under it: it sticks.
      if (state[k] == State::Sliding && -error * row.lambda > 0.0) state[k] = State::Active, changed = true;
      if (state[k] == State::Active) worst = std::max(worst, std::abs(error));
    }
    for (const int r : constraints) {
      const Row& row = R.rows[r];
      if (row.invK > 0.0) worst = std::max(worst, std::abs(row.target - R.velocityOf(row, v)) / row.norm);
    }
    solved.largest = worst;
    if (std::getenv("PL_DEBUG2")) {
      int a = 0, sl = 0, off = 0;
      for (std::size_t k = 0; k < m; ++k) (state[k] == State::Active ? a : state[k] == State::Sliding ? sl : off)++;
      std::fprintf(stderr, "   it %d changed %d worst %g active %d sliding %d off %d\n", iteration, (int)changed, worst, a, sl, off);
    }
    if (!changed && !(worst > tolerance)) {
      settled = true;
      break;
    }
    active = constraints;
    for (std::size_t k = 0; k < m; ++k)
      if (state[k] == State::Active && R.rows[contactRows[k]].invK > 0.0) active.push_back(contactRows[k]);
    if (active.empty()) {
      settled = true;
      break;
    }
    block.assign(active);
    if (!block.factorVelocities(R)) break;
    block.solveVelocities(R, v);
    // Normals that pull let go; friction past its cone slides at the bound.
    for (std::size_t k = 0; k < m; ++k) {
      Row& row = R.rows[contactRows[k]];
      if (row.kind == RowKind::Normal && state[k] == State::Active && row.lambda < 0.0) {
        R.move(row, -row.lambda, v);
        row.lambda = 0.0;
        state[k] = State::Off;
      }
    }
    for (std::size_t k = 0; k < m; ++k) {
      Row& row = R.rows[contactRows[k]];
      if (row.kind != RowKind::Friction || state[k] == State::Off) continue;
      const double bound = R.frictionBound(row);
      const double held =
          state[k] == State::Sliding ? std::copysign(bound, row.lambda) : std::clamp(row.lambda, -bound, bound);
      if (state[k] == State::Active && held != row.lambda) state[k] = State::Sliding;
      if (held != row.lambda) R.move(row, held - row.lambda, v);
      row.lambda = held;
    }
  }
  return solved;
}

}  // namespace particles::solve
