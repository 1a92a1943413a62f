#!/usr/bin/env bash
# The engine's threads beside other busy programs: the 8-way cloth at 64²,
# 128² and 256² under RK4 (the seed preset) and the stiff 64² cloth under
# xpbd at 1/60 s with its hanging lines (the demo's key 0), each stepped by
# `particle-lab run --csv` with --threads 1, --threads 2 and the default
# (the CPUs of the affinity mask), while 0, 1 and 2 busy processes that the
# script starts and stops itself (`yes threads-under-load >/dev/null`)
# compete for the CPUs.
# A run's time is the median of its rows' step_us; each case prints the
# medians over `rounds` runs (the three thread settings in turn, their
# order rotated each round) and the --threads 2 and default times over the
# one-thread time measured in the same conditions, then the share of
# --threads 2's steps that ran on more than one thread (the CSV's threads)
# and the range over the rounds of each round's --threads 2 and default time
# over its one-thread time (the spread of the ratios) with the median of those
# paired ratios (beside two busy programs the kernel leaves one of three busy
# threads a core to itself, and which one changes from run to run: the ratio
# of two medians over the rounds then compares runs of different placements,
# where a round's own ratio compares runs a few seconds apart), then the median over
# the rounds of each round's ratio of mean step times (the run's wall time
# stepping over its steps: beside busy programs a run's steps are often
# bimodal, a core to itself or shared with one of them, and its median step
# then tells which phase the run mostly saw, where the mean is what it cost).
#   bash scripts/threads-under-load.sh [build-dir] [rounds] [step-scale] [busy counts]
# (defaults: build, 5, 1, "0 1 2": about a second per run; a step-scale of
# 0.01 is a quick check of the script itself; busy counts "2" runs only the
# cases beside two busy processes.) No number here is asserted anywhere.
set -euo pipefail
build=${1:-build}
rounds=${2:-5}
scale=${3:-1}
levels=${4:-0 1 2}
lab="$build/demos/particle-lab"
[ -x "$lab" ] || { echo "threads-under-load: no $lab (build the particle-lab target first)" >&2; exit 2; }
[[ "$rounds" =~ ^[1-9][0-9]*$ ]] || { echo "threads-under-load: rounds must be a positive integer, got '$rounds'" >&2; exit 2; }
[[ "$scale" =~ ^([0-9]+\.?[0-9]*|\.[0-9]+)$ ]] && awk -v s="$scale" 'BEGIN { exit !(s > 0) }' ||
  { echo "threads-under-load: step-scale must be a number > 0, got '$scale'" >&2; exit 2; }
[[ "$levels" =~ ^[0-9]+( [0-9]+)*$ ]] ||
  { echo "threads-under-load: busy counts must be whole numbers separated by spaces, got '$levels'" >&2; exit 2; }

work=$(mktemp -d)
busy=()
stop_busy() {
  for pid in "${busy[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${busy[@]}"; do wait "$pid" 2>/dev/null || true; done
  busy=()
}
trap 'stop_busy; rm -rf "$work"' EXIT
trap 'exit 130' INT TERM

stiff="--scene cloth --param width=64 --param height=64 --param links=8 --param stiffness=400000 --param damping=0.5"
stiff+=" --param gravity=9.8 --param swing=0 --param drag=0 --param edge-contacts=0 --integrator xpbd"
stiff+=" --dt 0.016666666666666666 --lines"
# name | steps at scale 1 | arguments
cases=(
  "cloth 64^2 rk4|6000|--scene cloth --preset seed --param width=64 --param height=64 --param links=8 --integrator rk4"
  "cloth 128^2 rk4|1500|--scene cloth --preset seed --param width=128 --param height=128 --param links=8 --integrator rk4"
  "cloth 256^2 rk4|400|--scene cloth --preset seed --param width=256 --param height=256 --param links=8 --integrator rk4"
  "stiff 64^2 xpbd 1/60|100|$stiff"
)

# run ARGS...: median step_us of the run's steps (row 0, the initial state, left out), their mean,
# then the share of steps on more than one thread.
run() {
  "$lab" run "$@" --csv "$work/run.csv" >/dev/null 2>"$work/run.err" ||
    { echo "threads-under-load: particle-lab run $* failed: $(head -c 300 "$work/run.err")" >&2; exit 1; }
  awk -F, 'NR == 1 { for (k = 1; k <= NF; ++k) col[$k] = k; next } NR > 2 { print $col["step_us"] }' \
    "$work/run.csv" | median
  awk -F, 'NR == 1 { for (k = 1; k <= NF; ++k) col[$k] = k; next } NR > 2 { n++; sum += $col["step_us"] }
           END { print sum / n }' "$work/run.csv"
  awk -F, 'NR == 1 { for (k = 1; k <= NF; ++k) if ($k == "threads") c = k; next } NR > 2 { n++; if (c) more += $c > 1 }
           END { print c ? more / n : -1 }' "$work/run.csv"  # -1: a CSV without the threads column
}

median() { sort -g | awk '{ v[NR] = $1 } END { print NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
# ratios BASE OTHER: each round's value in OTHER over its value in BASE, a line each.
ratios() { paste "$1" "$2" | awk '{ print $2 / $1 }'; }
# round BASE OTHER: the median of those ratios and their range, "0.59 (0.57-0.60)".
round() {
  local r; r=$(ratios "$1" "$2" | sort -g)
  printf '%4.2f (%.2f-%.2f)' "$(median <<<"$r")" "$(head -1 <<<"$r")" "$(tail -1 <<<"$r")"
}

echo "threads under load: $(nproc) CPUs ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)); medians over $rounds runs of each run's median step_us"
printf '%-22s %4s %10s %20s %20s %8s %17s %17s %8s %8s %s\n' case busy "1 thread" "--threads 2" "default" ">1 used" \
  "2/1 round (range)" "d/1 round (range)" "mean 2/1" "mean d/1" "load average"
settings=("--threads 1" "--threads 2" "")
for competitors in $levels; do
  for ((c = 0; c < competitors; ++c)); do
    yes threads-under-load >/dev/null &  # named, so that a test can tell they are gone
    busy+=($!)
  done
  sleep 1  # the busy processes get going
  for entry in "${cases[@]}"; do
    IFS='|' read -r name steps args <<<"$entry"
    steps=$(awk -v s="$steps" -v f="$scale" 'BEGIN { n = int(s * f + 0.5); print n < 3 ? 3 : n }')
    : >"$work/times-0"; : >"$work/times-1"; : >"$work/times-2"; : >"$work/more"
    : >"$work/means-0"; : >"$work/means-1"; : >"$work/means-2"
    for ((r = 0; r < rounds; ++r)); do
      for ((k = 0; k < 3; ++k)); do
        s=$(((k + r) % 3))
        # shellcheck disable=SC2086
        run $args --steps "$steps" ${settings[$s]} >"$work/result"
        { read -r time; read -r mean; read -r more; } <"$work/result"
        echo "$time" >>"$work/times-$s"
        echo "$mean" >>"$work/means-$s"
        [ "$s" = 1 ] && echo "$more" >>"$work/more"
      done
    done
    one=$(median <"$work/times-0")
    two=$(median <"$work/times-1")
    default=$(median <"$work/times-2")
    # Line r of each times file is round r's run: the ratios of one round, their median and range.
    round2=$(round "$work/times-0" "$work/times-1")
    rounddef=$(round "$work/times-0" "$work/times-2")
    mean2=$(ratios "$work/means-0" "$work/means-1" | median)
    meandef=$(ratios "$work/means-0" "$work/means-2" | median)
    awk -v name="$name" -v busy="$competitors" -v one="$one" -v two="$two" -v def="$default" \
      -v more="$(median <"$work/more")" -v load="$(cut -d' ' -f1 /proc/loadavg)" \
      -v mean2="$mean2" -v meandef="$meandef" -v round2="$round2" -v rounddef="$rounddef" \
      'BEGIN { used = more < 0 ? "-" : sprintf("%.0f%%", 100 * more)
               printf "%-22s %4d %7.1f us %9.1f us (%5.2fx) %9.1f us (%5.2fx) %8s %s %s %7.2fx %7.2fx %s\n",
                      name, busy, one, two, two / one, def, def / one, used, round2, rounddef, mean2, meandef, load }'
  done
  stop_busy
done
