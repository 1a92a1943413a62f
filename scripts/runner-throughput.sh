#!/usr/bin/env bash
# Throughput of `particle-lab run` (steps per second of simulation, no CSV),
# median of 5 runs, for the scenes the runner's issue names. Expects a
# Release build in build/ (bash scripts/run-tests.sh makes one).
set -euo pipefail
cd "$(dirname "$0")/.."
lab=build/demos/particle-lab
median() { sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }
throughput() {
  for _ in 1 2 3 4 5; do
    "$lab" run "$@" | grep -oE '[0-9.e+]+ steps/s' | awk '{print $1}'
  done | median
}
row() { printf '%-44s %10s steps/s   (particle-lab run %s)\n' "$1" "$(throughput "${@:2}")" "${*:2}"; }
for integrator in euler symplectic-euler midpoint rk4 verlet implicit-euler dopri5; do
  row "test-chain cl=80, $integrator, dt 0.01" --scene test-chain --param cl=80 --integrator "$integrator" --steps 1000
done
row "cloth 10x10 4-way, rk4, dt 0.01" --scene cloth --steps 5000
row "cloth 64x64 4-way, rk4, dt 0.01" --scene cloth --param width=64 --param height=64 --steps 200
row "cloth 64x64 8-way, rk4, dt 0.01" --scene cloth --param width=64 --param height=64 --param links=8 --steps 200
row "hair 6 curls x 25, rk4, dt 0.002" --scene hair --steps 2000
