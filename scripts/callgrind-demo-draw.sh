#!/usr/bin/env bash
# Instructions the demo's drawing executes (valgrind --tool=callgrind, under
# Xvfb with Mesa's llvmpipe): the scene (Renderer::drawPane), the text and
# panel (Dear ImGui's RenderDrawData), the whole frame's drawing (App::draw),
# inclusive, on the calling thread; and the whole run's total, llvmpipe's
# rasteriser threads included. KEY's scene (default 3, the hair), FRAMES
# frames (default 40) in lockstep (one step a frame: the same run for any
# build), the panel shown. PARTICLE_DEMO=path measures another build, e.g.
# the one before a change, for a before/after in the same conditions.
set -euo pipefail
cd "$(dirname "$0")/.."
demo=${PARTICLE_DEMO:-./build/demos/particle-demo}
key=${1:-3}
frames=${2:-40}
out=$(mktemp)
trap 'rm -f "$out"' EXIT
xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" valgrind --tool=callgrind --callgrind-out-file="$out" \
  "$demo" --key "$key" --lockstep --frames "$frames" >/dev/null 2>&1
echo "key $key, $frames frames, $demo"
echo "total Ir: $(awk '/^summary:/ {print $2}' "$out")"
callgrind_annotate --inclusive=yes "$out" 2>/dev/null |
  grep -E 'demo::App::draw\(\)|Renderer::drawPane\(|RenderDrawData\(' | sed 's/ *\[.*//'
