#!/usr/bin/env bash
# The GNU-parallel recipe (scripts/sharded-lab.sh) on this machine:
#   sharded_lab.sh PROGRAM WORK EXPERIMENT
# runs the experiment's --quick mode as 3 shards under `parallel` and checks
# that the merged files equal an unsharded run's byte for byte.
PROGRAM=$1 WORK=$2 experiment=$3
source "$(dirname "$0")/common.sh"
rm -rf "$WORK" && mkdir -p "$WORK"
command -v parallel > /dev/null || { fail "GNU parallel is not installed (scripts/install-deps.sh)"; exit 1; }
"$PROGRAM" "$experiment" --quick --jobs 1 --out "$WORK/whole" > /dev/null 2>&1 || fail "unsharded run failed"
PROGRAM=$PROGRAM SLOTS=2 bash "$(dirname "$0")/../../scripts/sharded-lab.sh" "$experiment" "$WORK/sharded" 3 --quick --jobs 1 \
  > "$WORK/recipe.log" 2>&1 || fail "scripts/sharded-lab.sh failed: $(tail -n 3 "$WORK/recipe.log")"
if diff -r -x shards -x merge.log "$WORK/whole" "$WORK/sharded" > "$WORK/diff.txt"; then
  pass "$experiment: 3 shards under GNU parallel merged equal the unsharded run"
else
  fail "$experiment: merged output differs: $(head -c 400 "$WORK/diff.txt")"
fi
[ "$failures" = 0 ] || exit 1
