#!/usr/bin/env bash
# The measuring scripts on bench_step: bad arguments give one line on stderr
# and exit 2; a real run prints its per-run and summary lines. Their numbers
# are reported, never asserted.
# Usage: scripts.sh SOURCE_DIR BUILD_DIR WORK
source_dir=$1 build=$2 WORK=$3 PROGRAM=bash
source "$source_dir/tests/cli/common.sh"
rm -rf "$WORK" && mkdir -p "$WORK"
ratio=$source_dir/scripts/bench-ratio.sh callgrind=$source_dir/scripts/callgrind-step.sh
chain=$source_dir/scripts/callgrind-chain.sh
speedup=$source_dir/scripts/speedup-rounds.sh

expect ratio-runs-not-a-number 2 "^bench-ratio: runs must be a positive integer, got 'x'$" -- "$ratio" "$build" x
expect ratio-runs-zero 2 "^bench-ratio: runs must be a positive integer, got '0'$" -- "$ratio" "$build" 0
expect ratio-no-build 2 "^bench-ratio: no $WORK/none/tests/bench_step \(build the bench_step target first\)$" -- \
  "$ratio" "$WORK/none"
expect speedup-no-build 2 \
  "^speedup-rounds: no $WORK/none/tests/bench_cloth_reference \(build the bench_cloth_reference target first\)$" -- \
  "$speedup" "$WORK/none"
expect speedup-size 2 "^speedup-rounds: size must be 64, 128 or 256, got '100'$" -- "$speedup" "$build" 100
expect speedup-rounds-zero 2 "^speedup-rounds: rounds must be a positive integer, got '0'$" -- "$speedup" "$build" 64 0
load=$source_dir/scripts/threads-under-load.sh frames=$source_dir/scripts/demo-frame-times.sh
expect load-no-build 2 "^threads-under-load: no $WORK/none/demos/particle-lab \(build the particle-lab target first\)$" -- \
  "$load" "$WORK/none"
expect load-rounds 2 "^threads-under-load: rounds must be a positive integer, got '0'$" -- "$load" "$build" 0
expect load-scale 2 "^threads-under-load: step-scale must be a number > 0, got '-1'$" -- "$load" "$build" 1 -1
expect load-levels 2 "^threads-under-load: busy counts must be whole numbers separated by spaces, got '2,x'$" -- \
  "$load" "$build" 1 1 2,x
expect frames-load 2 "^demo-frame-times: --load takes a count >= 0, got 'x'$" -- "$frames" --load x
expect frames-threads 2 "^demo-frame-times: --threads takes a count >= 1, got '0'$" -- "$frames" --threads 0
expect frames-option 2 "^demo-frame-times: unknown option '--fast' \(--load N, --threads N, --key K\)$" -- "$frames" --fast
expect callgrind-no-build 2 \
  "^callgrind-step: no $WORK/none/tests/bench_step \(build the bench_step target first\)$" -- "$callgrind" "$WORK/none"
expect callgrind-chain-no-build 2 \
  "^callgrind-chain: no $WORK/none/tests/bench_chain_reference \(build the bench_chain_reference target first\)$" \
  -- "$chain" "$WORK/none"

# outputs NAME SCRIPT ARGS... -- REGEX...: exit 0 and a stdout line matching each regex.
outputs() {
  local name=$1 args=() got=0
  shift
  while [ "$1" != -- ]; do args+=("$1"); shift; done
  shift
  timeout 300 bash "${args[@]}" >"$WORK/$name.out" 2>"$WORK/$name.err" || got=$?
  if [ "$got" != 0 ]; then fail "$name: exit $got ($(head -c 300 "$WORK/$name.err"))"; return; fi
  for regex in "$@"; do
    grep -Eq -- "$regex" "$WORK/$name.out" || { fail "$name: no line matching '$regex'"; return; }
  done
  pass "$name"
}
outputs ratio-one-run "$ratio" "$build" 1 -- \
  "^run 1: rk4 [0-9.]+ us, dopri5 [0-9.]+ us \(CPU-time medians of 9\), dopri5 / rk4 = [0-9.]+$" \
  "^dopri5 / rk4 over 1 runs: median [0-9.]+, range [0-9.]+-[0-9.]+$"
outputs speedup-one-round "$speedup" "$build" 64 1 -- \
  "^round 1: 1 thread [0-9.]+ us, 2 threads [0-9.]+ us \(wall-time medians of 5\), speed-up [0-9.]+$" \
  "^speed-up 1 -> 2 threads 64\^2 over 1 rounds: median [0-9.]+, range [0-9.]+-[0-9.]+$"
# One round of every case and load at a hundredth of the steps: the script's table, and its
# busy processes gone afterwards.
outputs load-one-round "$load" "$build" 1 0.01 -- \
  "^case +busy +1 thread +--threads 2 +default +>1 used +2/1 round \(range\) +d/1 round \(range\) +mean 2/1 +mean d/1 +load average$" \
  "^cloth 64\^2 rk4 +0 +[0-9.]+ us +[0-9.]+ us \( *[0-9.]+x\) +[0-9.]+ us \( *[0-9.]+x\) +[0-9]+% +[0-9.]+ \([0-9.]+-[0-9.]+\) +[0-9.]+ \([0-9.]+-[0-9.]+\) +[0-9.]+x +[0-9.]+x [0-9.]+$" \
  "^stiff 64\^2 xpbd 1/60 +2 +[0-9.]+ us +[0-9.]+ us \( *[0-9.]+x\) +[0-9.]+ us \( *[0-9.]+x\) +[0-9]+% +[0-9.]+ \([0-9.]+-[0-9.]+\) +[0-9.]+ \([0-9.]+-[0-9.]+\) +[0-9.]+x +[0-9.]+x [0-9.]+$"
if pgrep -f '^yes threads-under-load$' >/dev/null; then fail "load-one-round: its busy processes are still running"; fi
if command -v valgrind >/dev/null; then
  outputs callgrind-counts "$callgrind" "$build" -- \
    "^chain80-dt10ms/dopri5: 1200 timed steps, [0-9]+ instructions per step$" "^dopri5 / rk4 = [0-9]+\.[0-9]{3}$"
  outputs callgrind-chain-counts "$chain" "$build" -- \
    "^rod chain 80: engine [0-9]+, reference [0-9]+ instructions per RK4 step, engine / reference = [0-9]+\.[0-9]{3}$"
else
  echo "valgrind is not installed: callgrind-step.sh's and callgrind-chain.sh's runs are not tested"
fi
finish
