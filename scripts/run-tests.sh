#!/usr/bin/env bash
# Installs what is needed, builds, and runs the whole test suite under Xvfb.
# With --sanitize: builds with ASan+UBSan and runs the unit tests, then the
# demo's hostile-input tests (2,000 random scripted events among them) and its advice
# (a worker thread started, cancelled and left running at exit) under Xvfb.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
jobs=$(nproc)
if [ "${1:-}" = "--sanitize" ]; then
  cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPARTICLES_SANITIZE=ON \
        -DPARTICLES_BUILD_GUI=ON -DPARTICLES_BUILD_BENCHMARKS=OFF
  cmake --build build-sanitize -j"$jobs"
  ASAN_OPTIONS=detect_leaks=1 ctest --test-dir build-sanitize -L unit --output-on-failure -j"$jobs"
  # The demo's own code is checked; leaks are not, as Mesa and X keep
  # allocations of their own until exit.
  ASAN_OPTIONS=detect_leaks=0 xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" \
    ctest --test-dir build-sanitize -L gui -R '^(DemoHostile|DemoAdvice)\.' --output-on-failure -j"$jobs"
else
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
  cmake --build build -j"$jobs"
  xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest --test-dir build --output-on-failure -j"$jobs"
fi
