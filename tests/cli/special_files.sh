#!/usr/bin/env bash
# Scene "files" that are not regular files or are too large, an output file another run is
# writing, and a scene name holding a newline and an escape sequence.
# Usage: special_files.sh PROGRAM DATA WORK
PROGRAM=$1 DATA=$2 WORK=$3
source "$(dirname "$0")/common.sh"
rm -rf "$WORK" && mkdir -p "$WORK"

# A FIFO with no writer: refused at once, not waited on.
mkfifo "$WORK/fifo"
expect fifo 2 'fifo: cannot read the file \(not a regular file\)$' -- run --scene-file "$WORK/fifo" --steps 1
# A sparse file beyond the 64 MiB limit: refused without reading it.
truncate -s 65M "$WORK/big.json"
expect too-large 2 'big.json: cannot read the file \(larger than the limit of 67108864 bytes\)$' -- \
  run --scene-file "$WORK/big.json" --steps 1
expect dev-null 2 '/dev/null: cannot read the file \(not a regular file\)$' -- run --scene-file /dev/null --steps 1

# Two runs given one output file: the second is refused and the first file stays complete.
"$PROGRAM" run --scene cloth --param width=30 --param height=30 --steps 100000000 --csv "$WORK/shared.csv" \
  >/dev/null 2>"$WORK/first.err" &
first=$!
if wait_for_rows "$WORK/shared.csv.partial" 3; then  # written under its temporary name until closed
  expect second-writer 2 "cannot write --csv file '.*shared.csv': another process is writing it$" -- \
    run --scene cloth --steps 10 --csv "$WORK/shared.csv"
  expect second-exporter 2 "cannot write --output file '.*shared.csv': another process is writing it$" -- \
    export --scene cloth -o "$WORK/shared.csv"
  kill -TERM $first
  code=0
  wait_for $first 30 || code=$?
  if [ $code = 130 ] && complete_csv "$WORK/shared.csv" && head -n 1 "$WORK/shared.csv" | grep -q '^step,t,'; then
    pass "first writer's file intact"
  else
    fail "first writer: exit $code, file complete: $(complete_csv "$WORK/shared.csv" && echo yes || echo no)"
  fi
else
  fail "the first writer wrote no rows"
  kill -KILL $first
fi

# A newline and ESC in a scene's name are escaped in the one-line summary.
code=0
"$PROGRAM" run --scene-file "$DATA/hostile/control-name.json" --steps 1 >"$WORK/name.out" 2>&1 || code=$?
if [ $code = 0 ] && [ "$(wc -l <"$WORK/name.out")" = 1 ] && ! grep -q $'\x1b' "$WORK/name.out" &&
   grep -Fq 'two\nlines \x1b[31mred with rk4' "$WORK/name.out"; then
  pass "control characters in the name"
else
  fail "control characters in the name: exit $code, output: $(od -c "$WORK/name.out" | head -5)"
fi
finish
