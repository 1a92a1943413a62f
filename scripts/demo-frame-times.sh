#!/usr/bin/env bash
# Frame times of particle-demo (wall time per frame: input, stepping, drawing
# and the buffer swap), from its state log's frame-times record: the default
# cloth, a 64 x 64 cloth with 8-way springs, the hair and the stiff 64 x 64
# cloth (k_s = 4e5) with xpbd at 60 Hz (number key 0), each run flat out under
# Xvfb for FRAMES frames (default 300) with the control panel shown. Real time
# is a median frame under 16.7 ms.
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
for scene in "--scene cloth" "--scene cloth --param width=64 --param height=64 --param links=8" "--scene hair" \
             "--key 0"; do
  # shellcheck disable=SC2086
  run $scene --frames "$frames" --log-state "$log" >/dev/null
  echo "$scene,$(awk -F, '$1 == "frame-times" {printf "%s,%.2f,%.2f,%.2f,%.2f", $2, $3, $4, $5, $6}' "$log")"
done
