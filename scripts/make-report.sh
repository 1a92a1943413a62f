#!/usr/bin/env bash
# Regenerates every CSV, table and figure of report/ and renders report/README.md.
#   bash scripts/make-report.sh          full experiments (the time of each is in report/README.md)
#   bash scripts/make-report.sh --quick  the CI-sized versions, to check the pipeline
set -euo pipefail
cd "$(dirname "$0")/.."
mode=()
if [ "${1:-}" = "--quick" ]; then mode=(--quick); fi
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j"$(nproc)" --target particle-lab
lab=./build/demos/particle-lab
data=report/data
mkdir -p "$data" report/figures
rm -f "$data"/*.csv "$data"/*.md

# key,value rows, the value quoted as RFC 4180 does (lab/values.cpp reads it back).
value() { printf '%s,"%s"\n' "$1" "${2//\"/\"\"}" >> "$data/values.csv"; }
printf 'key,value\n' > "$data/values.csv"
value machine.cpu "$(lscpu | sed -n 's/^Model name: *//p' | head -n 1)"
value machine.cores "$(lscpu | sed -n 's/^CPU(s): *//p' | head -n 1) ($(nproc) usable)"
value machine.load "$(cut -d' ' -f1-3 /proc/loadavg)"
value machine.compiler "$(c++ --version | head -n 1)"
value machine.date "$(date -u +%Y-%m-%d)"

# Each experiment's wall-clock time goes into values.csv (report.seconds.*).
started=$(date +%s)
for experiment in stability timing accuracy cost longtime extremes claims small-steps; do
  echo "== particle-lab $experiment ${mode[*]}" >&2
  begin=$(date +%s)
  "$lab" "$experiment" "${mode[@]}" --jobs "$(nproc)" --out "$data" > "$data/$experiment.log"
  value "report.seconds.$experiment" "$(( $(date +%s) - begin ))"
done
value report.seconds.total "$(( $(date +%s) - started ))"

# Every figure plots.gp draws is redrawn from this run's data; none is left stale.
find report/figures -name '*.png' ! -name 'demo-*' -delete
gnuplot -e "data='$data'; fig='report/figures'" report/plots.gp
"$lab" render-report --template report/template.md --data "$data" --out report/README.md
echo "report/README.md regenerated" >&2
"$lab" render-report --template report/readme-results.md --data "$data" --out README.md --section results
echo "README.md's results regenerated" >&2
