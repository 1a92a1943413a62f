#!/usr/bin/env bash
# Runs one laboratory experiment as N shards and merges them into the files an
# unsharded run writes:
#   scripts/sharded-lab.sh EXPERIMENT OUTDIR N [experiment options...]
# Shard K (particle-lab EXPERIMENT --shard K/N) runs the sweep cells whose
# index % N == K-1 into OUTDIR/shards/K; `particle-lab merge` then writes
# OUTDIR itself (CSVs, tables, values.csv), its tables and derived numbers
# computed from all cells.
#
# The shards run under GNU parallel (Debian's `parallel`):
#   HOSTS   --sshlogin list (default ":" — this machine only); e.g.
#           HOSTS=":,4/alice@node1,4/alice@node2" runs shards here and on two
#           hosts, 4 at a time on each. Every host needs particle-lab at
#           PROGRAM's path and OUTDIR on a shared file system (NFS, ...).
#   SLOTS   shards run at once per host (default: its cores, parallel's own rule)
#   PROGRAM particle-lab (default: build/demos/particle-lab, else the one on PATH)
# Add --jobs J among the options to give each shard J threads (shards and jobs
# compose; the results do not depend on either).
#
# As a Slurm job array instead (one shard per array task, then the merge):
#   SLURM=1 [CPUS=C] scripts/sharded-lab.sh EXPERIMENT OUTDIR N [options...]
# submits `sbatch --array=1-N --cpus-per-task=C` (C default 1) running
# `--shard $SLURM_ARRAY_TASK_ID/N --jobs $SLURM_CPUS_PER_TASK` (unless the
# options give --jobs), so each task runs its cells on the C CPUs Slurm gave
# it, and a merge job that starts when every task succeeded (--dependency=afterok).
set -euo pipefail
if [ $# -lt 3 ]; then
  echo "usage: $0 EXPERIMENT OUTDIR N [experiment options...]" >&2
  exit 2
fi
experiment=$1 out=$2 shards=$3
shift 3
case $shards in '' | *[!0-9]* | 0*) echo "$0: N must be a positive integer, got '$shards'" >&2; exit 2 ;; esac
cpus=${CPUS:-1}
case $cpus in '' | *[!0-9]* | 0*) echo "$0: CPUS must be a positive integer, got '$cpus'" >&2; exit 2 ;; esac
here=$(cd "$(dirname "$0")/.." && pwd)
program=${PROGRAM:-}
if [ -z "$program" ]; then
  if [ -x "$here/build/demos/particle-lab" ]; then program=$here/build/demos/particle-lab; else program=particle-lab; fi
fi
mkdir -p "$out/shards"
out=$(cd "$out" && pwd)  # absolute: the same path on every host

if [ "${SLURM:-0}" = 1 ]; then
  jobs='--jobs $SLURM_CPUS_PER_TASK'
  for option in "$@"; do case $option in --jobs | --jobs=*) jobs= ;; esac; done
  array=$(sbatch --parsable --array=1-"$shards" --cpus-per-task="$cpus" --job-name="lab-$experiment" \
    --output="$out/shards/%a.log" \
    --wrap "'$program' '$experiment' $*${jobs:+ $jobs} --shard \$SLURM_ARRAY_TASK_ID/$shards --out '$out/shards/'\$SLURM_ARRAY_TASK_ID")
  sbatch --dependency=afterok:"$array" --job-name="lab-$experiment-merge" --output="$out/merge.log" \
    --wrap "'$program' merge \$(seq -f '$out/shards/%g' $shards) --out '$out'"
  echo "submitted array job $array ($shards shards) and its merge; results in $out"
  exit 0
fi

slots=()
[ -n "${SLOTS:-}" ] && slots=(--jobs "$SLOTS")
parallel --will-cite --halt now,fail=1 --sshlogin "${HOSTS:-:}" "${slots[@]}" \
  "$program" "$experiment" "$@" --shard {}/"$shards" --out "$out/shards/{}" '>' "$out/shards/{}.log" '2>&1' \
  ::: $(seq 1 "$shards")
dirs=()
for k in $(seq 1 "$shards"); do dirs+=("$out/shards/$k"); done
"$program" merge "${dirs[@]}" --out "$out" > "$out/merge.log"
echo "merged $shards shards of $experiment into $out"
