#!/usr/bin/env bash
# The cloth's face-area floor against the cloth without it (--param
# area-stiffness=0), on the default 10 x 10 cloth, 4-way and 8-way:
#  - rest strain: the largest spring strain after 20 s hanging under RK4 at
#    the scene's dt (|x_j - x_i| / rest - 1 over the structural springs and
#    the 8-way cloth's diagonals, from the runner's last trajectory row);
#  - stable dt: RK4 run for 5 s at every dt of a 5% grid from 2 ms to 20 ms;
#    the largest dt at and below which every grid dt ran without diverging
#    (particle-lab run exits 3 on a blow-up), and any dt above it that ran.
# Usage: bash scripts/cloth-area-floor.sh   (needs build/demos/particle-lab)
set -euo pipefail
cd "$(dirname "$0")/.."
lab=./build/demos/particle-lab
[ -x "$lab" ] || { echo "cloth-area-floor: no $lab (build the particle-lab target first)" >&2; exit 2; }
traj=$(mktemp)
trap 'rm -f "$traj"' EXIT
grid=$(awk 'BEGIN { for (dt = 0.002; dt <= 0.0200001; dt *= 1.05) printf "%.6g ", dt }')
echo "links,area floor,largest strain at rest (20 s),stable dt (s),dt above it that ran"
for links in 4 8; do
  for floor in without with; do
    params=(--scene cloth --param "links=$links")
    [ "$floor" = without ] && params+=(--param area-stiffness=0)
    "$lab" run "${params[@]}" --integrator rk4 --steps 10000 --trajectory "$traj" --every 10000 >/dev/null
    strain=$(awk -F, -v links="$links" 'NR > 1 && $1 == 10000 { x[$3] = $4; y[$3] = $5 }
      function s(i, j, r) { d = sqrt((x[i] - x[j])^2 + (y[i] - y[j])^2) / r - 1; if (d > worst) worst = d }
      END { for (row = 0; row < 10; ++row) for (col = 0; col < 10; ++col) { i = 10 * row + col
              if (col < 9) s(i, i + 1, 0.05); if (row < 9) s(i, i + 10, 0.05)
              if (links == 8 && row < 9 && col < 9) { s(i, i + 11, 0.05 * sqrt(2)); s(i + 1, i + 10, 0.05 * sqrt(2)) } }
            printf "%.4f%%", 100 * worst }' "$traj")
    stable=none failed="" above=""
    for dt in $grid; do
      steps=$(awk -v dt="$dt" 'BEGIN { printf "%d", 5 / dt + 0.5 }')
      if "$lab" run "${params[@]}" --integrator rk4 --dt "$dt" --steps "$steps" >/dev/null 2>&1; then
        if [ -z "$failed" ]; then stable=$dt; else above="$above $dt"; fi
      else
        failed=${failed:-$dt}
      fi
    done
    echo "$links-way,$floor,$strain,$stable,${above:- none}"
  done
done
