#!/usr/bin/env bash
# The progress line of `run`: on a terminal (a pseudo-terminal made by
# script(1)) a run that lasts over a second shows
# "particle-lab: step N/M (P%), t = …" rewritten in place, and erases it before
# anything else is printed (here the interrupt line after SIGINT); with stderr
# a file there is no progress line at all.
# Usage: progress.sh PROGRAM DATA WORK
PROGRAM=$1 DATA=$2 WORK=$3
source "$(dirname "$0")/common.sh"
command -v script >/dev/null || { echo "no script(1): skipped"; exit 77; }
rm -rf "$WORK" && mkdir -p "$WORK"
args="run --scene cloth --param width=40 --param height=40 --steps 100000000"
script -qefc "exec '$PROGRAM' $args" "$WORK/tty.txt" >/dev/null 2>&1 </dev/null &
pid=$!
left=600  # 60 s for the first progress line
until grep -q 'particle-lab: step [0-9]*/100000000 ' "$WORK/tty.txt" 2>/dev/null; do
  [ $left -le 0 ] && break
  sleep 0.1
  left=$((left - 1))
done
# The pattern is anchored at both ends: other tests run the same command with more arguments.
pkill -INT -f "^$PROGRAM $args\$" || true
code=0
wait_for $pid 30 || code=$?
out=$(tr '\r' '\n' <"$WORK/tty.txt")
if ! grep -Eq '^particle-lab: step [0-9]+/100000000 \([0-9]+%\), t = [0-9.e+]+ s, [0-9.]+ s elapsed, ~[0-9.]+ s left' <<<"$out"; then
  fail "terminal: no progress line: $(head -c 300 "$WORK/tty.txt" | cat -v)"
elif ! grep -q $'\r\033\[Kparticle-lab: interrupted after step' "$WORK/tty.txt"; then
  fail "terminal: the progress line is not erased before the interrupt line: $(tail -c 300 "$WORK/tty.txt" | cat -v)"
else
  pass "terminal: progress shown, then erased (exit $code)"
fi

# Not a terminal: stderr holds only what the run says (nothing for a run that ends well).
"$PROGRAM" run --scene cloth --param width=40 --param height=40 --steps 4000 >"$WORK/plain.out" 2>"$WORK/plain.err" ||
  fail "file: the run failed"
if [ -s "$WORK/plain.err" ]; then fail "file: stderr is not empty: $(head -c 200 "$WORK/plain.err" | cat -v)"
else pass "file: no progress line"; fi
finish
