#!/usr/bin/env bash
# One-to-two-thread speed-up of the RK4 step on the 8-way cloth of size²
# particles (bench_cloth_reference's engine/<size> against
# engine-2threads/<size>, run beside the plain reference as the bench runs
# them): `rounds` fresh runs of 5 interleaved repetitions each, the speed-up
# of each run (wall-time medians measured in the same run), then the median
# and range over the rounds and the load average. Single runs on a noisy
# shared machine move by ±10%; the rounds show by how much.
#   bash scripts/speedup-rounds.sh [build-dir] [size] [rounds]   (defaults: build, 128, 6)
set -euo pipefail
build=${1:-build}
size=${2:-128}
rounds=${3:-6}
bench="$build/tests/bench_cloth_reference"
[ -x "$bench" ] || { echo "speedup-rounds: no $bench (build the bench_cloth_reference target first)" >&2; exit 2; }
[[ "$size" =~ ^(64|128|256)$ ]] || { echo "speedup-rounds: size must be 64, 128 or 256, got '$size'" >&2; exit 2; }
[[ "$rounds" =~ ^[1-9][0-9]*$ ]] || { echo "speedup-rounds: rounds must be a positive integer, got '$rounds'" >&2; exit 2; }
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
speedups=()
for ((r = 1; r <= rounds; ++r)); do
  line=$("$bench" --benchmark_filter="/$size(/|\$)" --benchmark_repetitions=5 \
    --benchmark_enable_random_interleaving=true --benchmark_color=false 2>/dev/null |
    sed -n "s/^speed-up 1 -> 2 threads $size^2 (wall time): \([0-9.]*\), 1 thread \([0-9.]*\) us, 2 threads \([0-9.]*\) us$/\1 \2 \3/p") || true
  [ -n "$line" ] || { echo "speedup-rounds: $bench printed no speed-up line for $size^2" >&2; exit 1; }
  read -r speedup one two <<<"$line"
  echo "round $r: 1 thread $one us, 2 threads $two us (wall-time medians of 5), speed-up $speedup"
  speedups+=("$speedup")
done
printf '%s\n' "${speedups[@]}" | sort -g | awk -v size="$size" '{ v[NR] = $1 }
  END { m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2;
        printf "speed-up 1 -> 2 threads %d^2 over %d rounds: median %.3f, range %.3f-%.3f\n", size, NR, m, v[1], v[NR] }'
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
