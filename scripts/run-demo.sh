#!/usr/bin/env bash
# Installs what is needed, builds, and launches the interactive demo.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
exec ./build/demos/particle-demo "$@"
