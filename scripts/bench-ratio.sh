#!/usr/bin/env bash
# CPU-time cost of a dopri5 call against an RK4 step on bench_step's
# chain80-dt10ms pair (the 80-rod chain at dt 10 ms, whole episodes): `runs`
# runs of 9 interleaved repetitions each; per run the two CPU-time medians and
# their ratio (measured in the same run), then the median and range of the
# ratios and the load average. Wall-clock numbers on a shared machine are
# noisy; scripts/callgrind-step.sh gives the repeatable instruction counts.
#   bash scripts/bench-ratio.sh [build-dir] [runs]      (defaults: build, 5)
set -euo pipefail
build=${1:-build}
runs=${2:-5}
bench="$build/tests/bench_step"
[ -x "$bench" ] || { echo "bench-ratio: no $bench (build the bench_step target first)" >&2; exit 2; }
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || { echo "bench-ratio: runs must be a positive integer, got '$runs'" >&2; exit 2; }
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
ratios=()
for ((r = 1; r <= runs; ++r)); do
  line=$("$bench" --benchmark_filter='^chain80-dt10ms/' --benchmark_repetitions=9 \
    --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true \
    --benchmark_format=csv 2>/dev/null |
    awk -F, '/_median"/ { split($1, n, "/"); cpu[n[2]] = $4 }
             END { if (!("rk4" in cpu) || !("dopri5" in cpu)) exit 1;
                   printf "%.2f %.2f %.3f", cpu["rk4"], cpu["dopri5"], cpu["dopri5"] / cpu["rk4"] }') ||
    { echo "bench-ratio: $bench did not report both medians" >&2; exit 1; }
  read -r rk4 dopri5 ratio <<<"$line"
  echo "run $r: rk4 $rk4 us, dopri5 $dopri5 us (CPU-time medians of 9), dopri5 / rk4 = $ratio"
  ratios+=("$ratio")
done
printf '%s\n' "${ratios[@]}" | sort -g | awk '{ v[NR] = $1 }
  END { m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2;
        printf "dopri5 / rk4 over %d runs: median %.3f, range %.3f-%.3f\n", NR, m, v[1], v[NR] }'
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
