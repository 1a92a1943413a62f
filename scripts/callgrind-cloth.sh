#!/usr/bin/env bash
# Instructions per timed step of bench_cloth_reference's 8-way spring cloth
# under callgrind: the engine's RK4 step (ParticleSystem::step called from
# engineStep, one thread) and the plain reference's (PlainCloth::step called
# from referenceStep), and their ratio, for each size given (default 64 128).
# Counts are repeatable (independent of load), unlike wall-clock medians;
# instructions are not time (a vector instruction does the work of several).
# callgrind runs the AVX2 clones of the engine's kernels where the processor
# has AVX2 (src/vector_kernels.h).
#   bash scripts/callgrind-cloth.sh [build-dir] [size...]   (default: build 64 128)
set -euo pipefail
build=${1:-build}
shift || true
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(64 128)
bench="$build/tests/bench_cloth_reference"
[ -x "$bench" ] || { echo "callgrind-cloth: no $bench (build the bench_cloth_reference target first)" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "callgrind-cloth: valgrind is not installed" >&2; exit 2; }
for size in "${sizes[@]}"; do
  [[ $size =~ ^(64|128|256)$ ]] || { echo "callgrind-cloth: size must be 64, 128 or 256, got '$size'" >&2; exit 2; }
done
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

perStep() {  # file callee caller → instructions per call
  callgrind_annotate --tree=caller --threshold=100 "$1" 2>/dev/null |
    grep -B3 "\*  .*$2" | grep "< .*$3" |
    sed -E 's/^ *([0-9,]+) .*\(([0-9,]+)x\).*/\1 \2/; s/,//g' | awk '{ print int($1 / $2) }'
}
for size in "${sizes[@]}"; do
  valgrind --tool=callgrind --callgrind-out-file="$out/$size.out" "$bench" --skip_check \
    --benchmark_filter="^(engine|reference)/$size\$" --benchmark_min_time=0.01 >/dev/null 2>&1
  engine=$(perStep "$out/$size.out" 'ParticleSystem::step(' 'engineStep(')
  reference=$(perStep "$out/$size.out" 'PlainCloth::step(' 'referenceStep(')
  awk -v s="$size" -v e="$engine" -v r="$reference" \
    'BEGIN { printf "cloth %d^2: engine %d, reference %d instructions per RK4 step, engine / reference = %.3f\n", s, e, r, e / r }'
done
