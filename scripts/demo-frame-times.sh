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
# text and panel's drawing on the last timed frame, and the paced ratio.
# No timing is asserted. PARTICLE_DEMO=path measures another build of the demo.
set -euo pipefail
cd "$(dirname "$0")/.."
demo=${PARTICLE_DEMO:-./build/demos/particle-demo}
frames=${1:-300}
log=$(mktemp)
trap 'rm -f "$log"' EXIT
run() {
  if [ -n "${DISPLAY:-}" ]; then "$demo" "$@"; else xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" "$demo" "$@"; fi
}
echo "scene,median ms,p10 ms,p90 ms,median stepping ms,scene draw ms,text and panel ms,paced real-time ratio  ($(nproc) cores: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); load $(cut -d' ' -f1 /proc/loadavg))"
for scene in "--key 1" "--key 2" "--key 3" "--key 4" "--key 5" "--key 6" "--key 7" "--key 8" "--key 9" "--key 0" \
             "--scene cloth --param width=64 --param height=64 --param links=8" \
             "--scene hourglass" "--scene newtons-cradle" "--scene capstan" "--scene rope-bridge" "--scene soft-body"; do
  # shellcheck disable=SC2086
  run $scene --frames "$frames" --realtime --log-state "$log" >/dev/null
  ratio=$(awk -F, '$1 == "real-time" {printf "%.3f", $3 / $4}' "$log")
  # shellcheck disable=SC2086
  run $scene --frames "$frames" --log-state "$log" >/dev/null
  echo "$scene,$(awk -F, '$1 == "frame-times" {printf "%.2f,%.2f,%.2f,%.2f,", $3, $4, $5, $6} $1 == "timing" {t = sprintf("%.2f,%.2f", $2, $3)} END {printf "%s", t}' "$log"),$ratio"
done
