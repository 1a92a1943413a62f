#!/usr/bin/env bash
# Instructions per timed step of bench_chain_reference's 80-rod chain under
# callgrind: the engine's RK4 step (ParticleSystem::step called from
# engineStep) and the plain O(m) reference's (PlainRk4::step called from
# referenceStep), and their ratio. Counts are repeatable (independent of
# load), unlike the CPU-time ratio the bench prints; instructions are not time
# (the reference's Thomas solve waits on two divisions a rod).
#   bash scripts/callgrind-chain.sh [build-dir]      (default: build)
set -euo pipefail
build=${1:-build}
bench="$build/tests/bench_chain_reference"
[ -x "$bench" ] || { echo "callgrind-chain: no $bench (build the bench_chain_reference target first)" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "callgrind-chain: valgrind is not installed" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
valgrind --tool=callgrind --callgrind-out-file="$out/chain.out" "$bench" \
  --benchmark_filter='^(engine|reference)/80$' --benchmark_min_time=0.3 >/dev/null 2>&1
callgrind_annotate --tree=caller --threshold=100 "$out/chain.out" 2>/dev/null >"$out/tree"
perStep() {  # callee caller → instructions per call
  grep -B3 "\*  .*$1" "$out/tree" | grep "< .*$2" |
    sed -E 's/^ *([0-9,]+) .*\(([0-9,]+)x\).*/\1 \2/; s/,//g' | awk '{ print int($1 / $2) }'
}
engine=$(perStep 'ParticleSystem::step(' 'engineStep(')
reference=$(perStep 'PlainRk4::step<' 'referenceStep(')
[ -n "$engine" ] && [ -n "$reference" ] || { echo "callgrind-chain: the profile named no timed steps" >&2; exit 1; }
awk -v e="$engine" -v r="$reference" \
  'BEGIN { printf "rod chain 80: engine %d, reference %d instructions per RK4 step, engine / reference = %.3f\n", e, r, e / r }'
