#!/usr/bin/env bash
# Ctrl-C during a laboratory experiment keeps only what it completed:
#   lab_interrupt.sh PROGRAM EXPERIMENT OUTDIR SECONDS [whole]
# sends SIGINT after SECONDS and checks the exit code (130), that every CSV
# written holds only complete rows (as many cells as its header), and that
# every quoted value (values.csv) is a number or text, never nan or empty.
# With `whole` (an experiment whose tables all derive from one sweep) no table
# and no value may be written at all.
set -u
program=$1 experiment=$2 out=$3 after=$4 whole=${5:-}
rm -rf "$out"
mkdir -p "$(dirname "$out")"
timeout --preserve-status -s INT "$after" "$program" "$experiment" --jobs 2 --out "$out" > /dev/null 2> "$out.stderr"
code=$?
fail() { echo "lab_interrupt: $*" >&2; exit 1; }
[ "$code" -eq 130 ] || fail "expected exit 130 after SIGINT, got $code ($(tail -n 2 "$out.stderr"))"
rows=0
for csv in "$out"/*.csv; do
  [ -e "$csv" ] || continue
  if [ "$(basename "$csv")" = values.csv ]; then
    [ -n "$whole" ] && fail "values.csv written from an interrupted run"
    grep -Eiq ',(-?nan|-?inf|)$' "$csv" && fail "values.csv quotes a value never measured: $(grep -Ei ',(-?nan|-?inf|)$' "$csv")"
    continue
  fi
  [ -z "$(tail -c 1 "$csv")" ] || fail "$csv: last row not ended by a newline"
  awk -F, 'NR == 1 { n = NF } NF != n { bad = 1; print FILENAME ": row " NR " has " NF " cells, header " n > "/dev/stderr" }
           END { exit bad }' "$csv" || fail "$csv has an incomplete row"
  rows=$((rows + $(wc -l < "$csv") - 1))
done
[ -n "$whole" ] && ls "$out"/*.md > /dev/null 2>&1 && fail "a table was written from an interrupted run: $(ls "$out"/*.md)"
echo "lab_interrupt: $experiment stopped with exit 130, $rows complete rows kept"
