#!/usr/bin/env bash
# Regenerates the README's pictures of the demo with the program's own
# --screenshot: the cloth with a corner pulled by a scripted mouse drag, the hair,
# and compare mode.
set -euo pipefail
cd "$(dirname "$0")/.."
demo=./build/demos/particle-demo
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
echo "wrote $out/demo-cloth.png $out/demo-hair.png $out/demo-compare.png"
