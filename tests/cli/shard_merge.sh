#!/usr/bin/env bash
# Sharded laboratory runs merge into exactly what an unsharded run writes:
#   shard_merge.sh PROGRAM WORK EXPERIMENT...
# For each experiment's --quick mode: shards 1/2 and 2/2 (on 2 threads each)
# merged must equal the unsharded run (1 thread) file for file, byte for byte
# — every CSV, table and values.csv. The experiments given here write no
# timing columns, so nothing is left out of the comparison. Then merge must
# refuse an incomplete set, a set mixing two experiments and a shard given
# twice, each with one line and exit 2.
PROGRAM=$1 WORK=$2
shift 2
source "$(dirname "$0")/common.sh"
rm -rf "$WORK" && mkdir -p "$WORK"
for experiment in "$@"; do
  dir=$WORK/$experiment
  "$PROGRAM" "$experiment" --quick --jobs 1 --out "$dir/whole" > /dev/null 2>&1 || fail "$experiment: unsharded run failed"
  shares=0 sweep=""
  for k in 1 2; do
    "$PROGRAM" "$experiment" --quick --jobs 2 --shard $k/2 --out "$dir/shard$k" > /dev/null 2>"$dir/shard$k.err" ||
      fail "$experiment: shard $k/2 failed"
    [ -e "$dir/shard$k/values.csv" ] && fail "$experiment: shard $k/2 wrote values.csv (a shard writes only its cells)"
    # The shard's last line (its last sweep's, labelled "EXPERIMENT" or "EXPERIMENT SWEEP") counts its own
    # cells: all of its share recorded.
    line=$(tail -n 1 "$dir/shard$k.err")
    if [[ $line =~ ^\[$experiment(\ [a-z]+)*\ shard\ $k/2\]\ finished\ in\ [0-9.]+\ s:\ ([0-9]+)\ of\ its\ ([0-9]+)\ cells\ recorded\ \(of\ ([0-9]+)\ in\ the\ sweep\)$ ]] &&
       [ "${BASH_REMATCH[2]}" = "${BASH_REMATCH[3]}" ] && [ "${BASH_REMATCH[2]}" -gt 0 ]; then
      shares=$((shares + BASH_REMATCH[3])) sweep=${BASH_REMATCH[4]}
    else
      fail "$experiment: shard $k/2 does not end counting its own cells: $line"
    fi
  done
  [ "$shares" = "$sweep" ] || fail "$experiment: the shards' shares ($shares) are not the sweep's $sweep cells"
  "$PROGRAM" merge "$dir/shard1" "$dir/shard2" --out "$dir/merged" > /dev/null 2>&1 || fail "$experiment: merge failed"
  files=$(ls "$dir/whole" | wc -l)
  if [ "$files" -gt 0 ] && diff -r "$dir/whole" "$dir/merged" > "$dir/diff.txt"; then
    pass "$experiment: 2 shards merged equal the unsharded run ($files files)"
  else
    fail "$experiment: merged output differs from the unsharded run: $(head -c 400 "$dir/diff.txt")"
  fi
done
first=$1 second=${2:-$1}
expect merge-incomplete 2 "^particle-lab: merge: incomplete shard set: shard 2/2 is missing$" -- \
  merge "$WORK/$first/shard1" --out "$WORK/incomplete"
expect merge-twice 2 "^particle-lab: merge: shard 1/2 given twice" -- \
  merge "$WORK/$first/shard1" "$WORK/$first/shard1" --out "$WORK/twice"
if [ "$first" != "$second" ]; then
  expect merge-mismatched 2 "^particle-lab: merge: shard 2/2 in .* ran a different experiment or options than" -- \
    merge "$WORK/$first/shard1" "$WORK/$second/shard2" --out "$WORK/mismatched"
fi
expect merge-not-a-shard 2 "^particle-lab: merge: no shard manifest '.*whole/shard.json'" -- \
  merge "$WORK/$first/whole" --out "$WORK/not-a-shard"
# An interrupted shard leaves no manifest: its set is refused.
rm -f "$WORK/$first/shard2/shard.json"
expect merge-unfinished 2 "^particle-lab: merge: no shard manifest .*shard2/shard.json' [(]not a shard, or its run did not finish[)]$" -- \
  merge "$WORK/$first/shard1" "$WORK/$first/shard2" --out "$WORK/unfinished"
[ "$failures" = 0 ] || exit 1
