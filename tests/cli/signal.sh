#!/usr/bin/env bash
# SIGINT and SIGTERM during `run --csv --trajectory`: the run stops at a step boundary, exits
# 130 with one line naming the last step, and both files hold complete rows up to that step
# (every row of the trajectory's last step, for every particle).
# Usage: signal.sh PROGRAM DATA WORK
PROGRAM=$1 DATA=$2 WORK=$3
source "$(dirname "$0")/common.sh"
rm -rf "$WORK" && mkdir -p "$WORK"
particles=1600  # the 40x40 cloth
for signal in INT TERM; do
  for delay in 0 0.02 0.05 0.13; do
    name="$signal-after-$delay"
    csv="$WORK/$name.csv" trajectory="$WORK/$name.trajectory.csv"
    "$PROGRAM" run --scene cloth --param width=40 --param height=40 --steps 100000000 \
      --csv "$csv" --trajectory "$trajectory" >"$WORK/$name.out" 2>"$WORK/$name.err" &
    pid=$!
    # Each file is written as NAME.partial and renamed when closed.
    if ! wait_for_rows "$csv.partial" 3; then fail "$name: no rows after 30 s"; kill -KILL $pid; continue; fi
    sleep "$delay"
    kill -"$signal" $pid
    code=0
    wait_for $pid 30 || code=$?
    if [ $code != 130 ]; then fail "$name: exit $code, expected 130"; continue; fi
    if [ "$(wc -l <"$WORK/$name.err")" != 1 ] ||
       ! grep -Eq '^particle-lab: interrupted after step [0-9]+ ' "$WORK/$name.err"; then
      fail "$name: stderr is not the one interrupt line: $(head -c 300 "$WORK/$name.err")"; continue
    fi
    last=$(sed -E 's/.*after step ([0-9]+) .*/\1/' "$WORK/$name.err")
    [ ! -e "$csv.partial" ] && [ ! -e "$trajectory.partial" ] || { fail "$name: a .partial file was left"; continue; }
    complete_csv "$csv" || { fail "$name: $csv has a cut or malformed row"; continue; }
    complete_csv "$trajectory" || { fail "$name: $trajectory has a cut or malformed row"; continue; }
    [ "$(tail -n 1 "$csv" | cut -d, -f1)" = "$last" ] || { fail "$name: $csv does not end at step $last"; continue; }
    [ "$(wc -l <"$csv")" = $((last + 2)) ] || { fail "$name: $csv does not hold steps 0..$last"; continue; }
    rows=$(awk -F, -v s="$last" '$1 == s' "$trajectory" | wc -l)
    [ "$rows" = $particles ] || { fail "$name: step $last has $rows trajectory rows, expected $particles"; continue; }
    [ "$(wc -l <"$trajectory")" = $(((last + 1) * particles + 1)) ] ||
      { fail "$name: $trajectory does not hold steps 0..$last"; continue; }
    pass "$name (stopped after step $last)"
  done
done
finish
