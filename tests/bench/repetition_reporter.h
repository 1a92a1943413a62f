#pragma once
// The console reporter that also keeps each repetition's CPU and wall time
// per iteration, by the run's full name (benchmark_name(): "engine/64",
// "engine-2threads/64/real_time"), for the ratios a benchmark prints at the end.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
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

// "ratio engine/reference <label>: median …": the ratio of the medians of the
// CPU time per iteration of runs `engine` and `reference`, with the range of
// the ratios of repetitions taken side by side; nothing if either did not run.
inline void printRatio(const RepetitionReporter& reporter, const std::string& engine, const std::string& reference,
                       const std::string& label) {
  const auto e = reporter.cpu.find(engine), r = reporter.cpu.find(reference);
  if (e == reporter.cpu.end() || r == reporter.cpu.end() || e->second.empty() || r->second.empty()) return;
  std::vector<double> ratios;
  for (std::size_t k = 0; k < std::min(e->second.size(), r->second.size()); ++k)
    ratios.push_back(e->second[k] / r->second[k]);
  std::printf("ratio engine/reference %s: median %.3f (repetitions %.3f-%.3f), engine %.2f us, reference %.2f us\n",
              label.c_str(), median(e->second) / median(r->second), *std::min_element(ratios.begin(), ratios.end()),
              *std::max_element(ratios.begin(), ratios.end()), median(e->second), median(r->second));
}

}  // namespace bench
