#!/usr/bin/env bash
# The measuring scripts on bench_step: bad arguments give one line on stderr
# and exit 2; a real run prints its per-run and summary lines. Their numbers
# are reported, never asserted.
#   bash tests/bench/scripts.sh SOURCE_DIR BUILD_DIR
set -u
source_dir=$1
build=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
pass() { echo "ok: $*"; }

# expect NAME CODE REGEX -- SCRIPT ARGS...: exit code CODE and, for CODE ≠ 0,
# stderr exactly one line matching REGEX; for CODE = 0, stdout matching REGEX.
expect() {
  local name=$1 code=$2 regex=$3
  shift 4
  local got=0
  timeout 300 bash "$source_dir/scripts/$1" "${@:2}" >"$work/out" 2>"$work/err" || got=$?
  if [ "$got" != "$code" ]; then fail "$name: exit $got, expected $code ($(head -c 300 "$work/err"))"; return; fi
  if [ "$code" != 0 ]; then
    if [ "$(wc -l <"$work/err")" != 1 ] || ! grep -Eq -- "$regex" "$work/err"; then
      fail "$name: stderr is not one line matching '$regex': $(head -c 300 "$work/err")"; return
    fi
  elif ! grep -Eq -- "$regex" "$work/out"; then
    fail "$name: stdout does not match '$regex': $(head -c 300 "$work/out")"; return
  fi
  pass "$name"
}

expect ratio-runs-not-a-number 2 "^bench-ratio: runs must be a positive integer, got 'x'$" -- bench-ratio.sh "$build" x
expect ratio-runs-zero 2 "^bench-ratio: runs must be a positive integer, got '0'$" -- bench-ratio.sh "$build" 0
expect ratio-no-build 2 "^bench-ratio: no $work/none/tests/bench_step \(build the bench_step target first\)$" -- \
  bench-ratio.sh "$work/none"
expect callgrind-no-build 2 "^callgrind-step: no $work/none/tests/bench_step \(build the bench_step target first\)$" -- \
  callgrind-step.sh "$work/none"
expect ratio-one-run 0 "dopri5 / rk4 over 1 runs: median [0-9.]+, range [0-9.]+-[0-9.]+" -- bench-ratio.sh "$build" 1
grep -Eq "^run 1: rk4 [0-9.]+ us, dopri5 [0-9.]+ us \(CPU-time medians of 9\), dopri5 / rk4 = [0-9.]+$" "$work/out" ||
  fail "ratio-one-run: no per-run line: $(head -c 300 "$work/out")"
if command -v valgrind >/dev/null; then
  expect callgrind-counts 0 "^dopri5 / rk4 = [0-9]+\.[0-9]{3}$" -- callgrind-step.sh "$build"
  grep -Eq "^chain80-dt10ms/dopri5: 1200 timed steps, [0-9]+ instructions per step$" "$work/out" ||
    fail "callgrind-counts: no dopri5 line: $(head -c 300 "$work/out")"
else
  echo "valgrind is not installed: callgrind-step.sh's run is not tested"
fi
[ "$failures" = 0 ] || { echo "$failures failure(s)"; exit 1; }
