#!/usr/bin/env bash
# Instructions per timed step of bench_step's chain80-dt10ms pair (RK4 and
# dopri5 on the 80-rod chain at dt 10 ms, whole episodes) under callgrind, and
# their ratio. Counts are repeatable (independent of load), unlike wall-clock
# medians. Only the calls of ParticleSystem::step made from runSteps are
# counted (the warm-up's steps are made from warmUp and left out).
#   bash scripts/callgrind-step.sh [build-dir]      (default: build)
set -euo pipefail
build=${1:-build}
bench="$build/tests/bench_step"
[ -x "$bench" ] || { echo "callgrind-step: no $bench (build the bench_step target first)" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "callgrind-step: valgrind is not installed" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

perStep() {  # name → "instructions calls" of the timed steps
  valgrind --tool=callgrind --callgrind-out-file="$out/$1.out" "$bench" \
    --benchmark_filter="^chain80-dt10ms/$1/" >/dev/null 2>&1
  callgrind_annotate --tree=caller --threshold=100 "$out/$1.out" 2>/dev/null |
    grep -B3 '\*  .*ParticleSystem::step(' | grep '< .*runSteps(' |
    sed -E 's/^ *([0-9,]+) .*\(([0-9,]+)x\).*/\1 \2/; s/,//g'
}
declare -A ir
for name in rk4 dopri5; do
  read -r total calls < <(perStep "$name")
  ir[$name]=$((total / calls))
  echo "chain80-dt10ms/$name: $calls timed steps, ${ir[$name]} instructions per step"
done
awk -v d="${ir[dopri5]}" -v r="${ir[rk4]}" 'BEGIN { printf "dopri5 / rk4 = %.3f\n", d / r }'
