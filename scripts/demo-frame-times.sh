#!/usr/bin/env bash
# Frame times of particle-demo (wall time per frame: input, stepping, drawing
# and the buffer swap), from its state log's frame-times record: the default
# cloth, a 64 x 64 cloth with 8-way springs and the hair, each run flat out
# under Xvfb for FRAMES frames (default 300) with the control panel shown.
# Prints per scene the median, 10th and 90th percentile of the frames after a
# 10-frame warm-up, and the median stepping part. No timing is asserted.
set -euo pipefail
cd "$(dirname "$0")/.."
demo=./build/demos/particle-demo
frames=${1:-300}
log=$(mktemp)
trap 'rm -f "$log"' EXIT
run() {
  if [ -n "${DISPLAY:-}" ]; then "$demo" "$@"; else xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" "$demo" "$@"; fi
}
echo "scene,frames,median ms,p10 ms,p90 ms,median stepping ms  ($(nproc) cores: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs))"
for scene in "cloth" "cloth --param width=64 --param height=64 --param links=8" "hair"; do
  # shellcheck disable=SC2086
  run --scene $scene --frames "$frames" --log-state "$log" >/dev/null
  echo "$scene,$(awk -F, '$1 == "frame-times" {printf "%s,%.2f,%.2f,%.2f,%.2f", $2, $3, $4, $5, $6}' "$log")"
done
