#!/usr/bin/env bash
# The Slurm recipe of scripts/sharded-lab.sh, with a stand-in sbatch on PATH
# that records its arguments (no Slurm needed):
#   sharded_lab_slurm.sh WORK
# CPUS=C asks for C CPUs per array task and passes --jobs $SLURM_CPUS_PER_TASK
# to each shard, unless the options give --jobs; a bad CPUS is refused.
WORK=$1 PROGRAM=/bin/true
source "$(dirname "$0")/common.sh"
recipe=$(dirname "$0")/../../scripts/sharded-lab.sh
rm -rf "$WORK" && mkdir -p "$WORK/bin"
cat > "$WORK/bin/sbatch" <<'STAND_IN'
#!/usr/bin/env bash
n=$(ls "$SBATCH_LOG" 2>/dev/null | wc -l)
mkdir -p "$SBATCH_LOG"
printf '%s\n' "$@" > "$SBATCH_LOG/$n"
echo $((1000 + n))
STAND_IN
chmod +x "$WORK/bin/sbatch"

# submit NAME ENV... -- OPTIONS...: runs the recipe for 3 shards of stability.
submit() {
  local name=$1 env=()
  shift
  while [ "$1" != -- ]; do env+=("$1"); shift; done
  shift
  env SBATCH_LOG="$WORK/$name" PATH="$WORK/bin:$PATH" SLURM=1 PROGRAM=/bin/true "${env[@]}" \
    bash "$recipe" stability "$WORK/$name.out" 3 "$@" > "$WORK/$name.log" 2>&1
}

submit cpus CPUS=4 -- --quick || fail "cpus: the recipe failed: $(cat "$WORK/cpus.log")"
if grep -qx -- '--cpus-per-task=4' "$WORK/cpus/0" &&
   grep -q -- "--quick --jobs \$SLURM_CPUS_PER_TASK --shard \$SLURM_ARRAY_TASK_ID/3 " "$WORK/cpus/0"; then
  pass "CPUS=4: --cpus-per-task=4, each shard --jobs \$SLURM_CPUS_PER_TASK"
else
  fail "CPUS=4: the array job's arguments: $(tr '\n' ' ' < "$WORK/cpus/0")"
fi
grep -q -- '--dependency=afterok:1000' "$WORK/cpus/1" && pass "merge after the array job" ||
  fail "merge job: $(tr '\n' ' ' < "$WORK/cpus/1")"

submit default -- --quick || fail "default: the recipe failed: $(cat "$WORK/default.log")"
grep -qx -- '--cpus-per-task=1' "$WORK/default/0" && pass "CPUS unset: one CPU per task" ||
  fail "CPUS unset: $(tr '\n' ' ' < "$WORK/default/0")"

submit own-jobs CPUS=2 -- --quick --jobs 3 || fail "own-jobs: the recipe failed: $(cat "$WORK/own-jobs.log")"
if grep -q -- '--jobs 3 --shard' "$WORK/own-jobs/0" && ! grep -q 'SLURM_CPUS_PER_TASK' "$WORK/own-jobs/0"; then
  pass "--jobs among the options is kept, not doubled"
else
  fail "own --jobs: $(tr '\n' ' ' < "$WORK/own-jobs/0")"
fi

code=0
submit bad CPUS=x -- --quick || code=$?
if [ "$code" = 2 ] && [ "$(wc -l < "$WORK/bad.log")" = 1 ] && grep -q "CPUS must be a positive integer, got 'x'" "$WORK/bad.log" &&
   [ ! -e "$WORK/bad" ]; then
  pass "CPUS=x: one line, exit 2, nothing submitted"
else
  fail "CPUS=x: exit $code: $(cat "$WORK/bad.log")"
fi
finish
