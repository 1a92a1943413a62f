#pragma once
// A sweep's results kept for the tables: what an experiment's tabulating
// functions read after every cell ran, so no row is written from inside a sweep.
#include <cstddef>
#include <functional>
#include <map>
#include <optional>

#include "lab/cells.h"

namespace lab {

// Results by cell number k (0 ≤ k < count): every cell in a run or a replay,
// the shard's own cells in a shard; a cell an interrupt cut short has none.
template <class Result>
using Results = std::map<std::size_t, Result>;

// `count` cells swept (sweep, cells.h) and their results kept.
template <class Result>
Results<Result> sweepResults(const LabOptions& options, std::size_t count,
                             const std::function<std::optional<Result>(std::size_t)>& compute,
                             const std::function<double(std::size_t)>& cost = {}) {
  Results<Result> results;
  sweep<Result>(
      options, count, compute, [&](std::size_t k, Result& result) { results.emplace(k, std::move(result)); }, cost);
  return results;
}

// `count` cells one at a time on this thread, in order (cell, cells.h), and
// their results kept: for measurements of wall time, which other work running
// beside them would disturb. With `stopAtInterrupt`, no cell starts after an
// interrupt. `after(k)` (optional) runs after each cell, computed here or not.
template <class Result>
Results<Result> resultsInTurn(const LabOptions& options, std::size_t count,
                              const std::function<std::optional<Result>(std::size_t)>& compute,
                              bool stopAtInterrupt, const std::function<void(std::size_t)>& after = {}) {
  Results<Result> results;
  for (std::size_t k = 0; k < count; ++k) {
    if (stopAtInterrupt && interrupted()) break;
    auto result = cell<Result>(options, [&] { return compute(k); });
    if (after) after(k);
    if (result) results.emplace(k, std::move(*result));
  }
  return results;
}

}  // namespace lab
