#!/usr/bin/env bash
# Regenerates the pictures of the demo (README.md, demos/gui/SCRIPTING.md) with its own
# --screenshot: the cloth with a corner pulled by a scripted mouse drag, the hair,
# compare mode, the cloth ripped by a pull in the wind, the gallery's five
# scenes, and a scene built by script in build mode, saved and run from its file.
set -euo pipefail
cd "$(dirname "$0")/.."
demo=$(pwd)/build/demos/particle-demo
out=report/figures
mkdir -p "$out"
run() {  # runs the demo under Xvfb unless a display is available
  if [ -n "${DISPLAY:-}" ]; then "$demo" "$@"; else xvfb-run -a -s "-screen 0 1280x1024x24" "$demo" "$@"; fi
}
script=$(mktemp)
trap 'rm -f "$script"' EXIT

# Cloth, 8-way: let its swing settle for 4 s, then pull its lower right
# corner (found in the state log at that frame) down and to the right.
cloth=(--scene cloth --param links=8 --param width=16 --param height=14)
log=$(mktemp)
run "${cloth[@]}" --frames 240 --log-state "$log"
read -r cx cy < <(awk -F, '$1 == "particle" && (best == "" || $4 - $5 > best) {best = $4 - $5; x = $4; y = $5}
                          END {print x, y}' "$log")
rm -f "$log"
awk -v x="$cx" -v y="$cy" 'BEGIN {
  print 240, "down world", x, y
  for (k = 1; k <= 40; ++k) print 240 + k, "move world", x + 0.35 * k / 40, y - 0.3 * k / 40
}' > "$script"
run "${cloth[@]}" --frames 400 --script "$script" --screenshot "$out/demo-cloth.png"

# Hair: after the ringlets settle, the mouse pulls the tip of the third strand
# (particle 2 * 30 + 29 at the default 30 particles a strand) 5 cm down and to
# the right, into its neighbour (disc contacts between strands).
log=$(mktemp)
run --scene hair --frames 120 --log-state "$log"
read -r tx ty < <(awk -F, '$1 == "particle" && $3 == 89 {print $4, $5}' "$log")
rm -f "$log"
awk -v x="$tx" -v y="$ty" 'BEGIN {
  print 120, "down world", x, y
  for (k = 1; k <= 90; ++k) print 120 + k, "move world", x + 0.04 * k / 90, y - 0.03 * k / 90
}' > "$script"
run --scene hair --frames 300 --script "$script" --screenshot "$out/demo-hair.png"
# Compare mode: the test chain at dt = 0.005 (2.5 times its default) under the
# four integrators, 3 s in.
run --scene test-chain --compare euler,symplectic-euler,midpoint,rk4 --dt 0.005 --frames 180 \
    --no-panel --window 1000x700 --screenshot "$out/demo-compare.png"
# Wind and tearing: the 8-way cloth in a steady 2 m/s wind with tearing at
# 15% strain; a particle in its middle (row 7, column 8) is pulled down and a
# little to the right until the cloth rips: each torn side takes its face out
# with its diagonals, so the rip runs along a line of faces across the cloth.
# The picture is 10 frames into the pull, the rip opening (23 links torn; the
# lower half falls away within 20 frames); no stepping budget, so every frame
# simulates its whole 1/60 s however loaded the machine.
torn=(--scene cloth --param links=8 --param width=16 --param height=14 --param wind=2 --param tear-strain=0.15
      --step-budget 1000000)
log=$(mktemp)
run "${torn[@]}" --frames 120 --log-state "$log"
read -r cx cy < <(awk -F, '$1 == "particle" && $3 == 7 * 16 + 8 {print $4, $5}' "$log")
awk -v x="$cx" -v y="$cy" 'BEGIN {
  print 120, "down world", x, y
  for (k = 1; k <= 60; ++k) print 120 + k, "move world", x + 0.1 * k / 60, y - 0.4 * k / 60
}' > "$script"
run "${torn[@]}" --frames 130 --script "$script" --screenshot "$out/demo-torn-wind.png" --log-state "$log"
awk -F, '$1 == "tearing" {print "torn cloth in wind: " $4 " links broken"}' "$log"
rm -f "$log"

# The gallery: each scene of the panel's list after it has run a while, the
# panel hidden, every frame its whole 1/60 s (no stepping budget): the
# hourglass 2.5 s, the cradle 0.55 s (the first ball's swing passed to the
# last, swung out), the capstan 1 s, the rope bridge 2 s, the soft bodies 2 s.
for shot in hourglass:150 newtons-cradle:33 capstan:60 rope-bridge:120 soft-body:120; do
  run --scene "${shot%%:*}" --no-panel --window 640x480 --step-budget 1000000 --frames "${shot##*:}" \
      --screenshot "$out/demo-${shot%%:*}.png"
done

# Build mode: a 3 x 3 cloth patch, its top row pinned, 12 springs and a disc
# below it, drawn by scripted clicks and drags from an empty scene, saved as a
# scene file and run; the picture is particle-demo --scene-file of that file.
built=$(mktemp -d)
awk 'BEGIN {
  f = 0
  print f++, "key e"; print f++, "key N"; print f++, "key n"; print f++, "edit new radius 0.01"
  for (row = 0; row < 3; ++row) {
    print f++, "edit new pinned", (row == 0 ? "true" : "false")
    for (col = 0; col < 3; ++col) { print f, "down world", 0.1 * col, 0.4 - 0.1 * row; print f++, "up world", 0.1 * col, 0.4 - 0.1 * row }
  }
  print f++, "key k"; print f++, "edit new stiffness 30"; print f++, "edit new damping 0.5"
  for (row = 0; row < 3; ++row) for (col = 0; col < 2; ++col) {
    print f++, "down world", 0.1 * col, 0.4 - 0.1 * row; print f++, "up world", 0.1 * col + 0.1, 0.4 - 0.1 * row }
  for (col = 0; col < 3; ++col) for (row = 0; row < 2; ++row) {
    print f++, "down world", 0.1 * col, 0.4 - 0.1 * row; print f++, "up world", 0.1 * col, 0.3 - 0.1 * row }
  print f++, "key D"; print f++, "edit new friction 0.3"; print f++, "edit build grid 0.05"
  print f++, "down world 0.1 0.0"; print f++, "up world 0.1 0.15"
  print f++, "edit build file patch.json"; print f++, "key s"; print f++, "key q"
}' > "$built/build.txt"
(cd "$built" && run --script build.txt --frames 1000 --lockstep >/dev/null)
run --scene-file "$built/patch.json" --frames 120 --screenshot "$out/demo-built.png"
rm -rf "$built"
echo "wrote $out/demo-cloth.png $out/demo-hair.png $out/demo-compare.png $out/demo-torn-wind.png $out/demo-built.png" \
     "and the gallery's $out/demo-{hourglass,newtons-cradle,capstan,rope-bridge,soft-body}.png"

# The web page: the picture its screenshot test took in headless Chromium
# (tests/web, ScreenshotParticlesWhereTheLogSays), when the web tests have run.
web=build/tests/web/output/page.png
if [ -f "$web" ]; then cp "$web" "$out/demo-web.png"; else echo "no $web: run the web tests (ctest -L web) for the page's picture" >&2; fi
