#!/usr/bin/env bash
# How evenly bench_cloth_reference's 8-way cloth RK4 step is shared by two
# threads, in instructions under callgrind (repeatable, independent of load):
# the main thread's instructions in one timed step (ParticleSystem::step
# called from engineStep), the worker's (every instruction of the second
# thread: it starts at the timed step's first parallel loop), and the
# one-thread step's; bound = one-thread / max(main, worker) is the speed-up
# the split allows if instructions were time and the threads never waited
# (barriers, memory bandwidth and other work on the machine lower it).
# OMP_WAIT_POLICY=passive, so that waiting threads sleep instead of spinning.
#   bash scripts/callgrind-threads.sh [build-dir] [size...]   (default: build 64 128)
set -euo pipefail
build=${1:-build}
shift || true
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(64 128)
bench="$build/tests/bench_cloth_reference"
[ -x "$bench" ] || { echo "callgrind-threads: no $bench (build the bench_cloth_reference target first)" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "callgrind-threads: valgrind is not installed" >&2; exit 2; }
for size in "${sizes[@]}"; do
  [[ $size =~ ^(64|128|256)$ ]] || { echo "callgrind-threads: size must be 64, 128 or 256, got '$size'" >&2; exit 2; }
done
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

perStep() {  # file callee caller → instructions per call
  callgrind_annotate --tree=caller --threshold=100 "$1" 2>/dev/null |
    grep -B3 "\*  .*$2" | grep "< .*$3" |
    sed -E 's/^ *([0-9,]+) .*\(([0-9,]+)x\).*/\1 \2/; s/,//g' | awk '{ print int($1 / $2) }'
}
total() {  # file → its program total
  callgrind_annotate "$1" 2>/dev/null | grep "PROGRAM TOTALS" | sed -E 's/^ *([0-9,]+) .*/\1/; s/,//g'
}
run() {  # size filter out-file [valgrind options]
  local size=$1 filter=$2 file=$3
  shift 3
  OMP_WAIT_POLICY=passive valgrind --tool=callgrind "$@" --callgrind-out-file="$file" "$bench" --skip_check \
    --benchmark_filter="$filter" --benchmark_min_time=0.01 >/dev/null 2>&1
}
for size in "${sizes[@]}"; do
  run "$size" "^engine/$size\$" "$out/one-$size.out"
  run "$size" "^engine-2threads/$size/" "$out/two-$size.out" --separate-threads=yes
  one=$(perStep "$out/one-$size.out" 'ParticleSystem::step(' 'engineStep(')
  main=$(perStep "$out/two-$size.out-01" 'ParticleSystem::step(' 'engineStep(')
  steps=$(callgrind_annotate --tree=caller --threshold=100 "$out/two-$size.out-01" 2>/dev/null |
    grep -B3 "\*  .*ParticleSystem::step(" | grep "< .*engineStep(" | sed -E 's/.*\(([0-9,]+)x\).*/\1/; s/,//g')
  worker=$(( $(total "$out/two-$size.out-02") / steps ))
  awk -v s="$size" -v o="$one" -v m="$main" -v w="$worker" 'BEGIN {
    x = m > w ? m : w
    printf "cloth %d^2: one thread %d; two threads: main %d, worker %d instructions per RK4 step; bound %.2f\n", s, o, m, w, o / x }'
done
