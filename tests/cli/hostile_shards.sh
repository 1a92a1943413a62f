#!/usr/bin/env bash
# Lab output directories that cannot be written, and shard sets that do not fit
# their experiment: each refused with one line and exit 2.
#   --out naming a file, "", a read-only directory, or a directory whose
#   shard.json is a directory;
#   a negative cell count or cell index;
#   a manifest of another format version, or whose recorded arguments run
#   merge instead of an experiment;
#   a cells file edited after its shard wrote it (the manifest's digest);
#   cells that are not the experiment's: its arguments gained an option, a
#   shard of another experiment, a missing key, a short array, a wrong type;
#   generated: cells of a wrong shape anywhere in a result (a field gone or
#   added, a value of another type, an integer written 1.5), each refused in
#   the program's words with --out left as it was (nothing is written before
#   every cell has read back).
# With "every-experiment" as a fourth argument (the Release suite), every
# experiment's --quick run is split into 2 to 4 shards, each of which must
# end with exit 0 and its manifest, and the shards must merge.
# Usage: hostile_shards.sh PROGRAM DATA WORK [every-experiment]
PROGRAM=$1 DATA=$2 WORK=$3 EVERY=${4:-}
source "$(dirname "$0")/common.sh"
rm -rf "$WORK" && mkdir -p "$WORK"

# Output directories that cannot be written.
touch "$WORK/a-file"
expect out-is-file 2 "^particle-lab: --out: cannot create the directory '.*a-file': Not a directory$" -- \
  longtime --quick --shard 1/2 --out "$WORK/a-file"
expect out-is-file-unsharded 2 "^particle-lab: --out: cannot create the directory '.*a-file': Not a directory$" -- \
  longtime --quick --out "$WORK/a-file"
expect out-empty 2 '^particle-lab: --out: expected a directory name, got an empty one$' -- \
  longtime --quick --shard 1/2 --out ""
mkdir -p "$WORK/manifest-dir/shard.json/inside"
expect manifest-is-dir 2 "^particle-lab: cannot write the shard manifest file '.*manifest-dir/shard.json': not a regular file$" -- \
  longtime --quick --shard 1/2 --out "$WORK/manifest-dir"
mkdir -p "$WORK/read-only" && chmod 555 "$WORK/read-only"
if [ "$(id -u)" != 0 ]; then
  expect out-read-only 2 "^particle-lab: cannot write the shard's cells file '.*read-only/cells.jsonl': Permission denied$" -- \
    longtime --quick --shard 1/2 --out "$WORK/read-only"
else
  echo "skipped out-read-only: root writes into a read-only directory"
fi

# Two good shards of longtime and one of stability.
for k in 1 2; do
  "$PROGRAM" longtime --quick --shard $k/2 --out "$WORK/good$k" >/dev/null 2>&1 || fail "longtime shard $k/2 failed"
done
"$PROGRAM" stability --quick --shard 2/2 --out "$WORK/stability2" >/dev/null 2>&1 || fail "stability shard 2/2 failed"
# The experiment's cell count and shard 2's share, as its manifests record them.
TOTAL=$(sed -n 's/^  "cells": \([0-9]*\),*$/\1/p' "$WORK/good1/shard.json")
SHARE2=$(wc -l <"$WORK/good2/cells.jsonl")
[ -n "$TOTAL" ] && [ "$SHARE2" -gt 0 ] || fail "cannot read the good shards' cell counts"
expect merge-good 0 "^\[longtime\] merged $TOTAL cells from 2 shards into" -- merge "$WORK/good1" "$WORK/good2" --out "$WORK/merged"

# tampered NAME SED: copies of the good shards as NAME1, NAME2, shard 1's manifest edited by SED.
tampered() {
  rm -rf "$WORK/$1"1 "$WORK/$1"2
  cp -r "$WORK/good1" "$WORK/$1"1 && cp -r "$WORK/good2" "$WORK/$1"2
  sed -i -E "$2" "$WORK/$1"1/shard.json "$WORK/$1"2/shard.json
}
tampered version 's/"format_version": 2/"format_version": 7/'
expect merge-version 2 "^particle-lab: merge: shard manifest '.*version1/shard.json' has format version 7, this particle-lab reads version 2" -- \
  merge "$WORK/version1" "$WORK/version2" --out "$WORK/out-version"
tampered noversion '/"format_version"/d'
expect merge-no-version 2 "^particle-lab: merge: shard manifest '.*noversion1/shard.json' has format version none," -- \
  merge "$WORK/noversion1" "$WORK/noversion2" --out "$WORK/out-noversion"
# Recorded arguments that would run merge again on the same shards.
tampered recurse "s|^    \"longtime\",\$|    \"merge\", \"$WORK/recurse1\",|; s|^    \"--quick\"\$|    \"$WORK/recurse2\"|"
expect merge-recursive-arguments 2 "^particle-lab: merge: shard manifest '.*recurse1/shard.json' records arguments that do not run 'longtime'$" -- \
  merge "$WORK/recurse1" "$WORK/recurse2" --out "$WORK/out-recurse"
tampered recurse-named "s|^    \"longtime\",\$|    \"merge\", \"$WORK/recurse-named1\",|; s|^    \"--quick\"\$|    \"$WORK/recurse-named2\"|; s|\"experiment\": \"longtime\"|\"experiment\": \"merge\"|"
expect merge-recursive-experiment 2 "^particle-lab: merge: the shards' manifest names 'merge', which is not an experiment" -- \
  merge "$WORK/recurse-named1" "$WORK/recurse-named2" --out "$WORK/out-recurse-named"
# A negative count or cell index is refused as written, never read as 2^64 - 1.
tampered negative-count "s/\"cells\": $TOTAL/\"cells\": -1/"
expect merge-negative-count 2 "^particle-lab: merge: malformed shard manifest '.*negative-count1/shard.json': cells must be an integer >= 0, got -1$" -- \
  merge "$WORK/negative-count1" "$WORK/negative-count2" --out "$WORK/out-negative-count"
# A count written with an exponent is quoted as written, not as the parser's 1000.0.
tampered exponent-count "s/\"cells\": $TOTAL/\"cells\": 1e3/"
expect merge-exponent-count 2 "^particle-lab: merge: malformed shard manifest '.*exponent-count1/shard.json': cells must be an integer >= 0, got 1e3$" -- \
  merge "$WORK/exponent-count1" "$WORK/exponent-count2" --out "$WORK/out-exponent-count"
# Arguments that gained an option: the experiment enumerates other cells than the shards hold.
tampered integrator 's|^    "--quick"$|    "--quick", "--integrator", "rk4"|'
LAST_LINE=1 expect merge-gained-integrator 2 "^particle-lab: merge: shard 1/2 in '.*integrator1' holds a cell [0-9]+ that is not this experiment's \(made by a different run or version\): " -- \
  merge "$WORK/integrator1" "$WORK/integrator2" --out "$WORK/out-integrator"

# The FNV-1a digest of a file, as a shard's manifest records it (perl-base is
# part of every Debian system).
digest() {
  perl -e 'use integer; local $/; my $d = <STDIN>; my $h = -3750763034362895579;
           for my $c (unpack("C*", $d)) { $h ^= $c; $h *= 1099511628211; } printf("%016x\n", $h)' <"$1"
}
# A cell edited after its shard wrote it: refused by the manifest's digest.
rm -rf "$WORK/edited1" "$WORK/edited2" && cp -r "$WORK/good1" "$WORK/edited1" && cp -r "$WORK/good2" "$WORK/edited2"
sed -i -E '1s/"last":[^,]*,/"last":"nan",/' "$WORK/edited1/cells.jsonl"
expect merge-edited-cell 2 "^particle-lab: merge: '.*edited1/cells.jsonl' is not the file its shard wrote \(its digest [0-9a-f]{16} differs from the manifest's [0-9a-f]{16}\)$" -- \
  merge "$WORK/edited1" "$WORK/edited2" --out "$WORK/out-edited"
[ "$(digest "$WORK/good1/cells.jsonl")" = "$(sed -n 's/.*"cells_digest": "\([0-9a-f]*\)".*/\1/p' "$WORK/good1/shard.json")" ] ||
  fail "the digest of good1/cells.jsonl is not its manifest's"

# cells NAME SED: copies of the good shards, shard 1's first cell edited by
# SED and its manifest's digest made to match (a shard of another version
# would carry a digest of its own cells): the cells' contents are checked.
cells() {
  rm -rf "$WORK/$1"1 "$WORK/$1"2
  cp -r "$WORK/good1" "$WORK/$1"1 && cp -r "$WORK/good2" "$WORK/$1"2
  sed -i -E "1$2" "$WORK/$1"1/cells.jsonl
  sed -i -E "s/\"cells_digest\": \"[0-9a-f]*\"/\"cells_digest\": \"$(digest "$WORK/$1"1/cells.jsonl)\"/" "$WORK/$1"1/shard.json
}
cells negative-cell 's/"cell":0/"cell":-1/'
expect merge-negative-cell 2 "^particle-lab: merge: malformed line 1 in '.*negative-cell1/cells.jsonl': cell must be an integer >= 0, got -1$" -- \
  merge "$WORK/negative-cell1" "$WORK/negative-cell2" --out "$WORK/out-negative-cell"
cells missing-key 's/"last":[^,]*,//'
LAST_LINE=1 expect merge-missing-key 2 "^particle-lab: merge: shard 1/2 in '.*missing-key1' holds a cell 0 that is not this experiment's \(made by a different run or version\): \\$: no field 'last'$" -- \
  merge "$WORK/missing-key1" "$WORK/missing-key2" --out "$WORK/out-missing-key"
cells short-array 's/"samples":\[\[([^],]*),[^]]*\]/"samples":[[\1]/'
LAST_LINE=1 expect merge-short-array 2 "^particle-lab: merge: shard 1/2 in '.*short-array1' holds a cell 0 that is not this experiment's \(made by a different run or version\): " -- \
  merge "$WORK/short-array1" "$WORK/short-array2" --out "$WORK/out-short-array"
cells wrong-type 's/"failed":false/"failed":"no"/'
LAST_LINE=1 expect merge-wrong-type 2 "^particle-lab: merge: shard 1/2 in '.*wrong-type1' holds a cell 0 that is not this experiment's \(made by a different run or version\): \\$\\.failed: expected true or false, got \"no\"$" -- \
  merge "$WORK/wrong-type1" "$WORK/wrong-type2" --out "$WORK/out-wrong-type"
cells not-a-number 's/"last":[^,]*,/"last":"many",/'
LAST_LINE=1 expect merge-not-a-number 2 "^particle-lab: merge: shard 1/2 in '.*not-a-number1' holds a cell 0 that is not this experiment's \(made by a different run or version\): \\$\\.last: expected a number \\(or \"nan\", \"inf\", \"-inf\"\\), got \"many\"$" -- \
  merge "$WORK/not-a-number1" "$WORK/not-a-number2" --out "$WORK/out-not-a-number"
# A shard of another experiment under longtime's manifest: its cells are stability's.
rm -rf "$WORK/foreign2" && cp -r "$WORK/good2" "$WORK/foreign2"
awk -v n="$SHARE2" 'NR <= n' "$WORK/stability2/cells.jsonl" >"$WORK/foreign2/cells.jsonl"
sed -i -E "s/\"cells_digest\": \"[0-9a-f]*\"/\"cells_digest\": \"$(digest "$WORK/foreign2/cells.jsonl")\"/" "$WORK/foreign2/shard.json"
# (Refused either as cells of the wrong index or as results that do not decode as longtime's.)
LAST_LINE=1 expect merge-foreign-cells 2 "^particle-lab: merge: shard 2/2 in '.*foreign2' holds (cell [0-9]+, not one of its own|a cell [0-9]+ that is not this experiment's) \(made by a different run or version\)" -- \
  merge "$WORK/good1" "$WORK/foreign2" --out "$WORK/out-foreign"
# A cell nested far deeper than any result (its digest made to match): refused while it is read, not by a crash.
rm -rf "$WORK/deep1" "$WORK/deep2" && cp -r "$WORK/good1" "$WORK/deep1" && cp -r "$WORK/good2" "$WORK/deep2"
python3 -c 'import sys; sys.stdout.write("{\"cell\":0,\"result\":" + "[" * 200000 + "]" * 200000 + "}\n")' >"$WORK/deep1/line"
{ cat "$WORK/deep1/line"; sed 1d "$WORK/good1/cells.jsonl"; } >"$WORK/deep1/cells.jsonl"
sed -i -E "s/\"cells_digest\": \"[0-9a-f]*\"/\"cells_digest\": \"$(digest "$WORK/deep1/cells.jsonl")\"/" "$WORK/deep1/shard.json"
expect merge-deep-cell 2 "^particle-lab: merge: malformed line 1 in '.*deep1/cells.jsonl': nested deeper than 64 levels$" -- \
  merge "$WORK/deep1" "$WORK/deep2" --out "$WORK/out-deep"
# A merge refused at a late cell writes nothing: the last cell of the shard holding the highest
# index (the experiment reads it back last) given a dt of [dt], its digest made to match.
rm -rf "$WORK/late1" "$WORK/late2" && cp -r "$WORK/good1" "$WORK/late1" && cp -r "$WORK/good2" "$WORK/late2"
late=$((TOTAL % 2 == 0 ? 2 : 1))
sed -i -E "/\"cell\":$((TOTAL - 1)),/s/\"dt\":([^,}]*)/\"dt\":[\\1]/" "$WORK/late$late/cells.jsonl"
sed -i -E "s/\"cells_digest\": \"[0-9a-f]*\"/\"cells_digest\": \"$(digest "$WORK/late$late/cells.jsonl")\"/" "$WORK/late$late/shard.json"
LAST_LINE=1 expect merge-late-cell 2 "^particle-lab: merge: shard $late/2 in '.*late$late' holds a cell $((TOTAL - 1)) that is not this experiment's \(made by a different run or version\): \\\$\.dt: expected a number, got \[" -- \
  merge "$WORK/late1" "$WORK/late2" --out "$WORK/out-late"
[ -e "$WORK/out-late" ] && fail "merge-late-cell: the refused merge wrote $(ls "$WORK/out-late" | tr '\n' ' ')"
# ... and leaves an existing --out as it was.
mkdir -p "$WORK/out-kept" && echo "key,value" >"$WORK/out-kept/values.csv"
LAST_LINE=1 expect merge-late-cell-kept 2 "holds a cell [0-9]+ that is not this experiment's" -- \
  merge "$WORK/late1" "$WORK/late2" --out "$WORK/out-kept"
[ "$(ls "$WORK/out-kept")" = values.csv ] && [ "$(cat "$WORK/out-kept/values.csv")" = key,value ] ||
  fail "merge-late-cell-kept: the refused merge changed --out: $(ls "$WORK/out-kept" | tr '\n' ' ')"

# Generated: a cell of each shard given a wrong shape somewhere in its result (a field removed
# or added, a value replaced by an object, an integer written 1.5), its digest made to match:
# refused in the program's words (never nlohmann's "[json.exception"), nothing written.
for k in $(seq 1 16); do
  rm -rf "$WORK/shape1" "$WORK/shape2" && cp -r "$WORK/good1" "$WORK/shape1" && cp -r "$WORK/good2" "$WORK/shape2"
  shard=$((k % 2 + 1))
  what=$(python3 - "$WORK/shape$shard/cells.jsonl" "$k" <<'PY'
import json, random, sys
path, seed = sys.argv[1], int(sys.argv[2])
rng = random.Random(seed)
lines = open(path).read().splitlines()
line = rng.randrange(len(lines))
row = json.loads(lines[line])
# Every place in the result: (container, key) pairs.
places = []
def walk(value):
    items = value.items() if isinstance(value, dict) else enumerate(value) if isinstance(value, list) else []
    for key, inner in items:
        places.append((value, key))
        walk(inner)
walk(row["result"])
kind = ["remove", "add", "object", "integer"][seed % 4]
objects = [(c, k) for c, k in places if isinstance(c, dict)]
integers = [(c, k) for c, k in places if type(c[k]) is int]
if (kind == "integer" and not integers) or (kind in ("remove", "add") and not objects): kind = "object"
if kind == "remove":
    container, key = rng.choice(objects); del container[key]
elif kind == "add":
    container, _ = rng.choice(objects)
    container["unexpected"] = 1
elif kind == "object":
    container, key = rng.choice(places); container[key] = {"x": 1}
else:
    container, key = rng.choice(integers); container[key] = 1.5
lines[line] = json.dumps(row, separators=(",", ":"))
open(path, "w").write("\n".join(lines) + "\n")
print(kind, "in line", line + 1)
PY
)
  sed -i -E "s/\"cells_digest\": \"[0-9a-f]*\"/\"cells_digest\": \"$(digest "$WORK/shape$shard/cells.jsonl")\"/" "$WORK/shape$shard/shard.json"
  got=0
  timeout 60 "$PROGRAM" merge "$WORK/shape1" "$WORK/shape2" --out "$WORK/out-shape" >/dev/null 2>"$WORK/shape.err" || got=$?
  if [ "$got" = 2 ] && [ "$(wc -l <"$WORK/shape.err")" = 1 ] && ! grep -q 'json\.exception' "$WORK/shape.err" &&
     grep -Eq "^particle-lab: merge: shard $shard/2 in '.*shape$shard' holds a cell [0-9]+ that is not this experiment's \(made by a different run or version\): \\\$[^ ]*: (expected|no field)" "$WORK/shape.err" &&
     [ ! -e "$WORK/out-shape" ]; then
    pass "merge-shape-$k ($what)"
  else
    fail "merge-shape-$k ($what): exit $got, out $([ -e "$WORK/out-shape" ] && echo written || echo absent): $(head -c 300 "$WORK/shape.err")"
  fi
  rm -rf "$WORK/out-shape"
done

# Every experiment's shards end with exit 0 and their manifest (small-steps' shards ended with
# 130, no signal sent, and no manifest: another shard's cell was taken for an interrupt), and
# they merge. The shard counts are drawn from a fixed seed.
if [ "$EVERY" = every-experiment ]; then
  RANDOM=20261218
  for experiment in timing accuracy extremes claims cost longtime small-steps; do
    n=$((RANDOM % 3 + 2))
    dirs=()
    for k in $(seq 1 "$n"); do
      dir="$WORK/every-$experiment-$k"
      rm -rf "$dir"
      got=0
      timeout 300 "$PROGRAM" "$experiment" --quick --jobs 2 --shard "$k/$n" --out "$dir" >/dev/null 2>"$dir.err" || got=$?
      if [ "$got" = 0 ] && [ -f "$dir/shard.json" ]; then pass "every-$experiment-shard-$k/$n"
      else fail "every-$experiment-shard-$k/$n: exit $got, manifest $([ -f "$dir/shard.json" ] && echo yes || echo no): $(tail -c 300 "$dir.err")"; fi
      dirs+=("$dir")
    done
    got=0
    timeout 300 "$PROGRAM" merge "${dirs[@]}" --out "$WORK/every-$experiment-merged" >/dev/null 2>"$WORK/every-$experiment.err" || got=$?
    [ "$got" = 0 ] && pass "every-$experiment-merge ($n shards)" ||
      fail "every-$experiment-merge: exit $got: $(tail -c 300 "$WORK/every-$experiment.err")"
  done
fi
finish
