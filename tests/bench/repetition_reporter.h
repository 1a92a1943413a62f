#pragma once
// The console reporter that also keeps each repetition's CPU and wall time
// per iteration, by the run's full name (benchmark_name(): "engine/64",
// "engine-2threads/64/real_time"), for the ratios a benchmark prints at the end.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

namespace bench {

class RepetitionReporter : public benchmark::ConsoleReporter {
 public:
  std::map<std::string, std::vector<double>> cpu, wall;
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs)
      if (r.run_type == Run::RT_Iteration && !r.error_occurred) {
        cpu[r.benchmark_name()].push_back(r.GetAdjustedCPUTime());
        wall[r.benchmark_name()].push_back(r.GetAdjustedRealTime());
      }
    ConsoleReporter::ReportRuns(runs);
  }
};

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

}  // namespace bench
