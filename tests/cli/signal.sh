#!/usr/bin/env bash
# SIGINT and SIGTERM during `run --csv --trajectory` (and SIGTERM inside one long CG solve):
# the run stops at a step boundary, exits
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
    if ! wait_for_rows "$csv.partial" 3 $pid; then
      if kill -0 $pid 2>/dev/null; then kill -KILL $pid; wait $pid 2>/dev/null; fail "$name: no rows after 30 s"
      else code=0; wait $pid || code=$?; fail "$name: ended (exit $code) before writing rows: $(head -c 300 "$WORK/$name.err"); $(df -h "$WORK" | tail -n 1)"
      fi
      continue
    fi
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
    rm -f "$csv" "$trajectory"  # each run's trajectory is tens of megabytes
  done
done

# A signal inside one long step: a 16000-rod chain under Jacobi CG (about 16000
# iterations a solve, 25 s a step here). The solve watches the cancel flag
# each iteration, so the run answers within a few seconds, not after the
# step; the cut step is not written: the CSV ends with the step before it.
"$PROGRAM" export --scene test-chain --param cl=16000 >"$WORK/long-chain.json" || fail "export of the long chain failed"
# CG without its work bound (maxCgWork 0), so that one solve takes seconds and
# the signal arrives inside it.
sed -i -e 's/"method":"direct"/"method":"cg"/' -e 's/"maxCgWork":[0-9.e+]*/"maxCgWork":0/' "$WORK/long-chain.json"
grep -q '"method":"cg"' "$WORK/long-chain.json" || fail "the long chain's solver is not CG"
grep -q '"maxCgWork":0[,}]' "$WORK/long-chain.json" || fail "the long chain's CG keeps its work bound"
csv="$WORK/long-chain.csv"
"$PROGRAM" run --scene-file "$WORK/long-chain.json" --steps 1000 --csv "$csv" >"$WORK/long-chain.out" 2>"$WORK/long-chain.err" &
pid=$!
# The output file is opened after the handler is installed (loading takes several
# seconds, a minute and more under the sanitizers on a loaded machine); a second later the
# first step's solve is running.
wait_for_rows "$csv.partial" 0 $pid 180 || fail "long-chain: no output file after 180 s"
sleep 1
if kill -0 $pid 2>/dev/null; then
  kill -TERM $pid
  code=0
  wait_for $pid 5 || code=$?
  if [ $code = 124 ]; then fail "long-chain: still running 5 s after SIGTERM (the solve did not stop)"
  elif [ $code != 130 ]; then fail "long-chain: exit $code, expected 130"
  elif ! grep -Eq '^particle-lab: interrupted after step [0-9]+ ' "$WORK/long-chain.err"; then
    fail "long-chain: no interrupt line: $(head -c 300 "$WORK/long-chain.err")"
  else
    last=$(grep -E '^particle-lab: interrupted after step' "$WORK/long-chain.err" | sed -E 's/.*after step ([0-9]+) .*/\1/')
    complete_csv "$csv" && [ "$(tail -n 1 "$csv" | cut -d, -f1)" = "$last" ] &&
      [ "$(wc -l <"$csv")" = $((last + 2)) ] && pass "long-chain (stopped inside step $((last + 1)))" ||
      fail "long-chain: $csv does not end whole at step $last"
  fi
else
  fail "long-chain: ended before the signal: $(head -c 300 "$WORK/long-chain.err")"
fi
finish
