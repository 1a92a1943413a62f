#!/usr/bin/env bash
# Failed writes end the program with one line and exit 4: the lab's outputs and render-report
# on /dev/full, then the runner and the lab on a small full tmpfs (where this machine allows a
# private mount; skipped with a message otherwise). The runner's /dev/full cases are in
# tests/CMakeLists.txt.
# Usage: full_disk.sh PROGRAM DATA WORK
PROGRAM=$1 DATA=$2 WORK=$3
source "$(dirname "$0")/common.sh"
rm -rf "$WORK" && mkdir -p "$WORK"
tested=0

if [ -w /dev/full ]; then
  tested=1
  mkdir -p "$WORK/lab-csv"
  ln -s /dev/full "$WORK/lab-csv/timing.csv"
  LAST_LINE=1 expect lab-csv 4 "cannot write the CSV file '.*timing.csv': No space left on device$" -- \
    timing --quick --out "$WORK/lab-csv"
  echo "report text" >"$WORK/template.md"
  expect render-report 4 "cannot write the rendered report file '/dev/full': No space left on device$" -- \
    render-report --template "$WORK/template.md" --data "$WORK" --out /dev/full
else
  echo "no writable /dev/full: its lab cases are skipped"
fi

mkdir -p "$WORK/small"
if unshare -m --propagation private true 2>/dev/null &&
   unshare -m --propagation private mount -t tmpfs -o size=64k tmpfs "$WORK/small" 2>/dev/null; then
  tested=1
  # Inside one private mount namespace: a 64 KiB tmpfs that the outputs fill.
  unshare -m --propagation private bash -c '
    source "$1/common.sh"; PROGRAM=$2; WORK=$3
    mount -t tmpfs -o size=64k tmpfs "$WORK/small" || { fail "mount"; finish; }
    expect tmpfs-csv 4 "cannot write --csv file .*: No space left on device$" -- \
      run --scene cloth --steps 5000 --csv "$WORK/small/cloth.csv"
    expect tmpfs-trajectory 4 "cannot write --trajectory file .*: No space left on device$" -- \
      run --scene cloth --steps 5000 --trajectory "$WORK/small/cloth-trajectory.csv"
    rm -f "$WORK/small"/*
    head -c 60000 /dev/zero >"$WORK/small/filler"
    LAST_LINE=1 expect tmpfs-lab 4 "cannot write the (CSV|table|values) file .*: No space left on device$" -- \
      timing --quick --out "$WORK/small/lab"
    finish' inner "$(dirname "$0")" "$PROGRAM" "$WORK" || failures=$((failures + 1))
else
  echo "skipped: this machine does not allow a private tmpfs mount (unshare -m, mount -t tmpfs)"
fi
[ $tested = 1 ] || { echo "skipped: neither /dev/full nor a small tmpfs is available"; exit 77; }
finish
