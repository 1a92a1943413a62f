#!/usr/bin/env bash
# The web page's sizes, its time to the first frame and each scene's
# real-time ratio in headless Chromium (WebGL 2 on SwiftShader, one thread),
# beside the desktop's paced ratio (scripts/demo-frame-times.sh, Xvfb and
# llvmpipe), as a table in report/data/web_demo.md (the report's demo
# section) and on stdout. FRAMES (default 300) frames per scene, REPEATS
# (default 5) fresh loads for the first frame. Builds nothing: run
# scripts/build-web.sh, scripts/install-web-test-deps.sh and the desktop
# build first. No timing is asserted anywhere.
set -euo pipefail
cd "$(dirname "$0")/.."
frames=${1:-300}
repeats=${2:-5}
page=build-web
size() { stat -c %s "$1"; }
gz() { gzip -9 -c "$1" | wc -c; }
kb() { awk -v b="$1" 'BEGIN {printf "%.0f", b / 1024}'; }
web=$(mktemp)
desktop=$(mktemp)
trap 'rm -f "$web" "$desktop"' EXIT
# WEB_TIMES=file: the page's from an earlier run of tests/web/measure_page.js.
if [ -n "${WEB_TIMES:-}" ]; then cp "$WEB_TIMES" "$web"; else
  PARTICLES_WEB_PAGE=$PWD/$page NODE_PATH=$PWD/build/web-tests/node_modules \
    node tests/web/measure_page.js "$frames" "$repeats" > "$web"
fi
# DESKTOP_TIMES=file: the desktop's table from an earlier run of demo-frame-times.sh.
if [ -n "${DESKTOP_TIMES:-}" ]; then cp "$DESKTOP_TIMES" "$desktop"; else bash scripts/demo-frame-times.sh "$frames" > "$desktop"; fi
machine="$(nproc) cores: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); load $(cut -d' ' -f1 /proc/loadavg)"
{
  echo "Page: particle-demo.wasm $(kb "$(size $page/particle-demo.wasm)") KiB ($(kb "$(gz $page/particle-demo.wasm)") KiB gzipped; the scene files and"
  echo "the font embedded in it), particle-demo.js $(kb "$(size $page/particle-demo.js)") KiB ($(kb "$(gz $page/particle-demo.js)") KiB gzipped),"
  echo "particle-demo.html $(kb "$(size $page/particle-demo.html)") KiB. First frame after navigation: median"
  awk -F, '$1 == "first frame ms" {printf "%s ms (%s to %s ms) over '"$repeats"' loads of ?key=1.\n", $2, $3, $4}' "$web"
  echo ""
  echo "| scene | page (headless Chromium) | desktop (Xvfb) |"
  echo "| --- | --- | --- |"
  # The desktop's table also times the gallery; its first rows are the page's scenes, in order.
  paste -d, <(grep -v '^first frame' "$web") <(tail -n +2 "$desktop" | head -n "$(grep -vc '^first frame' "$web")") |
    awk -F, '{name = $1; gsub(/&/, " ", name); printf "| %s | %s | %s |\n", name, $2, $NF}'
  echo ""
  echo "Real-time ratio: simulated over wall seconds, $frames frames paced at 60 per second with the panel shown;"
  echo "the page on one thread, the desktop on OpenMP's threads ($machine at the end)."
} | tee report/data/web_demo.md
