#!/usr/bin/env bash
# --threads of `particle-lab run`: a count above the CPUs of the affinity
# mask is lowered to that count with one note on stderr, and the CSV's
# threads column never passes it (under `taskset -c 0`: every step on one
# thread); a count within it gives no note, and the steps run on one thread
# or on that count.
# Usage: threads.sh PROGRAM DATA WORK
PROGRAM=$1 DATA=$2 WORK=$3
source "$(dirname "$0")/common.sh"
rm -rf "$WORK" && mkdir -p "$WORK"
cloth="run --scene cloth --param width=64 --param height=64 --param links=8 --steps 12"

# threads_column FILE: the CSV's threads column, one value a line, row 0 left out.
threads_column() {
  awk -F, 'NR == 1 { for (k = 1; k <= NF; ++k) if ($k == "threads") c = k; next } NR > 2 { print $c }' "$1"
}

cpus=$(nproc)
# shellcheck disable=SC2086
expect above-cpus 0 \
  "^particle-lab: note: --threads 1024 is more than the $cpus CPUs? this process may run on \(its affinity mask\): using $cpus$" \
  -- $cloth --threads 1024 --csv "$WORK/above.csv"
if [ "$(threads_column "$WORK/above.csv" | sort -u | awk -v most="$cpus" '$1 < 1 || $1 > most' | wc -l)" = 0 ] &&
   [ "$(threads_column "$WORK/above.csv" | wc -l)" = 12 ]; then
  pass "above-cpus: 12 steps, each on 1 to $cpus threads"
else
  fail "above-cpus: threads column $(threads_column "$WORK/above.csv" | tr '\n' ' ')"
fi

if command -v taskset >/dev/null; then
  first=$(taskset -pc $$ | sed 's/.*: //; s/[,-].*//')  # the first CPU this shell may use
  printf '#!/bin/sh\nexec taskset -c %s "%s" "$@"\n' "$first" "$1" >"$WORK/one-cpu.sh"
  chmod +x "$WORK/one-cpu.sh"
  PROGRAM=$WORK/one-cpu.sh
  # shellcheck disable=SC2086
  expect one-cpu 0 "^particle-lab: note: --threads 2 is more than the 1 CPU this process may run on \(its affinity mask\): using 1$" \
    -- $cloth --threads 2 --csv "$WORK/one.csv"
  PROGRAM=$1
  if [ "$(threads_column "$WORK/one.csv" | sort -u | tr '\n' ' ')" = "1 " ]; then
    pass "one-cpu: every step on one thread"
  else
    fail "one-cpu: threads column $(threads_column "$WORK/one.csv" | tr '\n' ' ')"
  fi
else
  echo "no taskset: the one-CPU case is not tested"
fi

if [ "$cpus" -ge 2 ]; then
  # shellcheck disable=SC2086
  if ! timeout 60 "$PROGRAM" $cloth --threads 2 --csv "$WORK/two.csv" >/dev/null 2>"$WORK/two.err"; then
    fail "within-cpus: exit $? ($(head -c 300 "$WORK/two.err"))"
  elif [ -s "$WORK/two.err" ]; then
    fail "within-cpus: stderr $(head -c 300 "$WORK/two.err")"
  elif [ "$(threads_column "$WORK/two.csv" | awk '$1 != 1 && $1 != 2' | wc -l)" != 0 ] ||
       [ "$(threads_column "$WORK/two.csv" | wc -l)" != 12 ]; then
    fail "within-cpus: threads column $(threads_column "$WORK/two.csv" | tr '\n' ' ') (expected 12 steps on 1 or 2)"
  else
    pass "within-cpus: no note; 12 steps, each on 1 or 2 threads"
  fi
fi
finish
