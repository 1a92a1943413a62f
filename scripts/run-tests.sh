#!/usr/bin/env bash
# Installs what is needed, builds, and runs the whole test suite under Xvfb.
# With --sanitize: builds with ASan+UBSan and runs the unit tests (but the
# *Sweep suites), then the
# demo's hostile-input tests (2,000 random scripted events among them) and its advice
# (a worker thread started, cancelled and left running at exit) under Xvfb.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
jobs=$(nproc)
if [ "${1:-}" = "--sanitize" ]; then
  # Line tables only (-g1): enough for the sanitizers' stack traces, and much
  # cheaper to compile and link than full debug information.
  cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPARTICLES_SANITIZE=ON \
        "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG" -DPARTICLES_BUILD_GUI=ON -DPARTICLES_BUILD_BENCHMARKS=OFF
  cmake --build build-sanitize -j"$jobs"
  # Suites named *Sweep repeat full simulations over integrators and cases
  # (the code paths the other unit tests reach); the Release run keeps them.
  ASAN_OPTIONS=detect_leaks=1 ctest --test-dir build-sanitize -L unit -E 'Sweep\.' --output-on-failure -j"$jobs"
  # The demo's own code is checked; leaks are not, as Mesa and X keep
  # allocations of their own until exit.
  ASAN_OPTIONS=detect_leaks=0 xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" \
    ctest --test-dir build-sanitize -L gui -R '^(DemoHostile|DemoAdvice)\.' --output-on-failure -j"$jobs"
else
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
  cmake --build build -j"$jobs"
  xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest --test-dir build --output-on-failure -j"$jobs"
fi
