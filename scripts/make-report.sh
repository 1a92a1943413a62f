#!/usr/bin/env bash
# Regenerates every CSV, table and figure of report/ and renders report/README.md.
#   bash scripts/make-report.sh                  full experiments (the time of each is in report/README.md)
#   bash scripts/make-report.sh --quick          the CI-sized versions, to check the pipeline
#   bash scripts/make-report.sh cost accuracy    only these experiments again, the others' data kept;
#                                                every figure is redrawn and the report rendered again
set -euo pipefail
cd "$(dirname "$0")/.."
all=(stability timing accuracy cost longtime extremes claims small-steps)
mode=()
chosen=()
for arg in "$@"; do
  case "$arg" in
    --quick) mode=(--quick) ;;
    *)
      if [[ " ${all[*]} " != *" $arg "* ]]; then
        echo "make-report.sh: unknown experiment '$arg' (one of: ${all[*]}, or --quick)" >&2
        exit 2
      fi
      chosen+=("$arg") ;;
  esac
done
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j"$(nproc)" --target particle-lab
lab=./build/demos/particle-lab
data=report/data
mkdir -p "$data" report/figures

# key,value rows, the value quoted as RFC 4180 does (lab/values.cpp reads it back);
# a key set again replaces its row.
value() {
  if [ -f "$data/values.csv" ]; then
    awk -F, -v key="$1" '$1 != key' "$data/values.csv" > "$data/values.csv.new"
    mv "$data/values.csv.new" "$data/values.csv"
  fi
  printf '%s,"%s"\n' "$1" "${2//\"/\"\"}" >> "$data/values.csv"
}
if [ ${#chosen[@]} -eq 0 ]; then
  # A whole run starts from nothing: no row of an earlier run survives it.
  # web_demo.md is scripts/web-demo-times.sh's (the page timed in a browser): kept.
  chosen=("${all[@]}")
  find "$data" -maxdepth 1 \( -name '*.csv' -o -name '*.md' \) ! -name web_demo.md -delete
  printf 'key,value\n' > "$data/values.csv"
  value machine.cpu "$(lscpu | sed -n 's/^Model name: *//p' | head -n 1)"
  value machine.cores "$(lscpu | sed -n 's/^CPU(s): *//p' | head -n 1) ($(nproc) usable)"
  value machine.load "$(cut -d' ' -f1-3 /proc/loadavg)"
  value machine.compiler "$(c++ --version | head -n 1)"
  value machine.date "$(date -u +%Y-%m-%d)"
elif [ ! -f "$data/values.csv" ]; then
  echo "make-report.sh: $data/values.csv is missing: run every experiment first (no arguments)" >&2
  exit 2
fi

# Each experiment's wall-clock time goes into values.csv (report.seconds.*);
# the total is their sum, whichever of them this run repeated.
for experiment in "${chosen[@]}"; do
  echo "== particle-lab $experiment ${mode[*]}" >&2
  begin=$(date +%s)
  "$lab" "$experiment" "${mode[@]}" --jobs "$(nproc)" --out "$data" > "$data/$experiment.log"
  value "report.seconds.$experiment" "$(( $(date +%s) - begin ))"
done
value report.seconds.total "$(awk -F, '$1 ~ /^report\.seconds\./ && $1 != "report.seconds.total" \
  { gsub(/"/, "", $2); total += $2 } END { print total }' "$data/values.csv")"

# Every figure plots.gp draws is redrawn from this run's data; none is left stale.
find report/figures -name '*.png' ! -name 'demo-*' -delete
gnuplot -e "data='$data'; fig='report/figures'" report/plots.gp
"$lab" render-report --template report/template.md --data "$data" --out report/README.md
echo "report/README.md regenerated" >&2
"$lab" render-report --template report/readme-results.md --data "$data" --out README.md --section results
echo "README.md's results regenerated" >&2
