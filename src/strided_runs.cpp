#include "strided_runs.h"

#include <algorithm>
#include <numeric>

namespace particles {

StridedRuns findStridedRuns(const std::vector<int>& first, const std::vector<int>& second, int maxLength,
                            int minLength, const std::vector<int>& keys) {
  const int n = static_cast<int>(first.size());
  auto stride = [&](int k) { return second[k] - first[k]; };
  auto key = [&](int k) { return keys.empty() ? 0 : keys[k]; };
  std::vector<int> sorted(n);
  std::iota(sorted.begin(), sorted.end(), 0);
  std::stable_sort(sorted.begin(), sorted.end(), [&](int a, int b) {
    return stride(a) != stride(b) ? stride(a) < stride(b) : first[a] < first[b];
  });
  std::vector<StridedRun> found;  // begin: into sorted
  std::vector<int> left;
  for (int s = 0; s < n;) {
    int e = s + 1;
    while (e < n && e - s < maxLength && stride(sorted[e]) == stride(sorted[s]) &&
           first[sorted[e]] == first[sorted[e - 1]] + 1 && key(sorted[e]) == key(sorted[s]))
      ++e;
    if (e - s >= minLength && stride(sorted[s]) != 0)
      found.push_back({s, first[sorted[s]], stride(sorted[s]), e - s});
    else
      left.insert(left.end(), sorted.begin() + s, sorted.begin() + e);
    s = e;
  }
  std::stable_sort(found.begin(), found.end(), [](const StridedRun& a, const StridedRun& b) {
    return a.first != b.first ? a.first < b.first : a.stride < b.stride;
  });
  StridedRuns result;
  for (const StridedRun& r : found) {
    result.runs.push_back({static_cast<int>(result.order.size()), r.first, r.stride, r.length});
    result.order.insert(result.order.end(), sorted.begin() + r.begin, sorted.begin() + r.begin + r.length);
  }
  result.leftBegin = static_cast<int>(result.order.size());
  std::sort(left.begin(), left.end());
  result.order.insert(result.order.end(), left.begin(), left.end());
  return result;
}

}  // namespace particles
