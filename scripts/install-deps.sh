#!/usr/bin/env bash
# Installs the Debian packages particle-lab needs to build, test and run, and
# any others named as arguments (scripts/build-web.sh's, for instance).
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  libeigen3-dev libgtest-dev libbenchmark-dev libcli11-dev nlohmann-json3-dev libboost-dev libfmt-dev
  freeglut3-dev libglu1-mesa-dev libgl1-mesa-dev libimgui-dev libpng-dev
  xvfb xauth gnuplot-nox parallel valgrind help2man python3 universal-ctags util-linux
  "$@"
)
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
