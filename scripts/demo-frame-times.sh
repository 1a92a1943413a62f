#!/usr/bin/env bash
# Frame times and real-time ratio of particle-demo under Xvfb, from its state
# log's frame-times, real-time and timing records: every number key's scene
# (1-9, 0), a 64 x 64 cloth with 8-way springs and the gallery's five scenes
# (the panel's list), each for FRAMES frames
# (default 300) with the control panel shown, paced at 60 Hz (--realtime) as a
# user sees it. Real time is a ratio of at least 0.95 (simulated over wall
# seconds, all frames after the first); a paced frame cannot be shorter than
# 16.7 ms, so the frame times are those of flat-out runs, made second.
# Prints per scene: median, 10th and 90th percentile frame (ms, after a
# 10-frame warm-up, flat out), the median stepping part, the scene's and the
# text and panel's drawing (medians over the frames the demo times, one in
# 30 after the first, GL work included; the text and panel's 10th and 90th
# percentiles and the count of timed frames beside them), and the paced ratio.
# No timing is asserted.
#   bash scripts/demo-frame-times.sh [--load N] [--threads N] [--key K] [FRAMES]
# --load N: N busy processes (`yes demo-frame-times >/dev/null`, started and
# stopped by the script) compete for the CPUs while it runs; --threads N: the
# demo's --threads (default: its own, the CPUs of the affinity mask); --key K:
# that number key's scene only. PARTICLE_DEMO=path measures another build of the demo.
set -euo pipefail
cd "$(dirname "$0")/.."
demo=${PARTICLE_DEMO:-./build/demos/particle-demo}
load=0 threads=() only=
while [ $# -gt 0 ]; do
  case $1 in
    --load) load=${2:-}; shift 2 || true
            [[ "$load" =~ ^[0-9]+$ ]] || { echo "demo-frame-times: --load takes a count >= 0, got '$load'" >&2; exit 2; } ;;
    --threads) [[ "${2:-}" =~ ^[1-9][0-9]*$ ]] || { echo "demo-frame-times: --threads takes a count >= 1, got '${2:-}'" >&2; exit 2; }
               threads=(--threads "$2"); shift 2 ;;
    --key) [[ "${2:-}" =~ ^[0-9]$ ]] || { echo "demo-frame-times: --key takes a digit, got '${2:-}'" >&2; exit 2; }
           only=$2; shift 2 ;;
    -*) echo "demo-frame-times: unknown option '$1' (--load N, --threads N, --key K)" >&2; exit 2 ;;
    *) break ;;
  esac
done
frames=${1:-300}
[[ "$frames" =~ ^[1-9][0-9]*$ ]] || { echo "demo-frame-times: FRAMES must be a positive integer, got '$frames'" >&2; exit 2; }
log=$(mktemp)
busy=()
stop_busy() {
  for pid in "${busy[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${busy[@]}"; do wait "$pid" 2>/dev/null || true; done
}
trap 'stop_busy; rm -f "$log"' EXIT
trap 'exit 130' INT TERM
for ((c = 0; c < load; ++c)); do
  yes demo-frame-times >/dev/null &
  busy+=($!)
done
run() {
  if [ -n "${DISPLAY:-}" ]; then "$demo" "$@"; else xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" "$demo" "$@"; fi
}
scenes=("--key 1" "--key 2" "--key 3" "--key 4" "--key 5" "--key 6" "--key 7" "--key 8" "--key 9" "--key 0"
        "--scene cloth --param width=64 --param height=64 --param links=8"
        "--scene hourglass" "--scene newtons-cradle" "--scene capstan" "--scene rope-bridge" "--scene soft-body")
[ -n "$only" ] && scenes=("--key $only")
echo "scene,median ms,p10 ms,p90 ms,median stepping ms,scene draw ms,text and panel ms,text and panel p10,p90,timed frames,paced real-time ratio  ($(nproc) cores: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); load $(cut -d' ' -f1 /proc/loadavg); $load busy processes; ${threads[*]:-default threads})"
for scene in "${scenes[@]}"; do
  # shellcheck disable=SC2086
  run $scene "${threads[@]}" --frames "$frames" --realtime --log-state "$log" >/dev/null
  ratio=$(awk -F, '$1 == "real-time" {printf "%.3f", $3 / $4}' "$log")
  # shellcheck disable=SC2086
  run $scene "${threads[@]}" --frames "$frames" --log-state "$log" >/dev/null
  echo "$scene,$(awk -F, '$1 == "frame-times" {printf "%.2f,%.2f,%.2f,%.2f,", $3, $4, $5, $6} $1 == "timing" {t = sprintf("%.2f,%.2f,%.2f,%.2f,%d", $6, $7, $8, $9, $5)} END {printf "%s", t}' "$log"),$ratio"
done
