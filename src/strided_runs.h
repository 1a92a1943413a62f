#pragma once
// Pairs of particles (first[k], second[k]) grouped into strided runs:
// (a, a + d), (a + 1, a + 1 + d), …, (a + L − 1, a + L − 1 + d), one stride d,
// whose particles lie in two contiguous stretches of the state, so that a
// run is one vectorisable loop. Used by the spring batch (forces/spring_batch.h)
// and the compliant distance constraints (xpbd/distance.h).
//
// The pairs may come in any order: they are sorted by stride and first
// particle, and each maximal sequence of consecutive first particles with
// one stride (and one key, when keys are given: pairs with different keys
// never share a run) is cut into runs of at most maxLength. Runs shorter
// than minLength, and pairs of stride 0, are left over.
#include <vector>

namespace particles {

struct StridedRun {
  int begin = 0;   // its pairs are order[begin, begin + length)
  int first = 0;   // a
  int stride = 0;  // d
  int length = 0;  // L
};

struct StridedRuns {
  // Pair indices: the runs' pairs run by run, then the pairs left over in
  // ascending index.
  std::vector<int> order;
  std::vector<StridedRun> runs;  // ordered by first particle, then stride
  int leftBegin = 0;             // order[leftBegin, end) are left over
};

StridedRuns findStridedRuns(const std::vector<int>& first, const std::vector<int>& second, int maxLength,
                            int minLength, const std::vector<int>& keys = {});

}  // namespace particles
