#!/usr/bin/env bash
# Builds the demo as a web page: build-web/particle-demo.html with its .js and
# .wasm (the scene files and the panel's font embedded), a static folder that
# any web server can serve (scripts/run-web-demo.sh serves it).
# Installs what it needs from Debian's packages: Emscripten, and the sources
# of Dear ImGui (libimgui-dev ships its library and headers, not the sources
# em++ must compile), fetched with `apt-get source` through a private source
# list and package lists under build-web/apt, so the machine's own stay as
# they were. The engine, CLI11, nlohmann-json, {fmt} and Eigen are the
# desktop's (cmake/ParticlesWebDeps.cmake); OpenMP is off (one thread).
set -euo pipefail
cd "$(dirname "$0")/.."
# dpkg-dev unpacks the sources; fonts-dejavu-core has the panel's font.
bash scripts/install-deps.sh emscripten dpkg-dev fonts-dejavu-core
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
# Emscripten runs its JavaScript tools (acorn) under /usr/bin/node, which
# may be a build other than Debian's that does not look in Debian's folder.
export NODE_PATH=/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}

mkdir -p build-web
# Dear ImGui's sources at the version of the desktop's libimgui-dev.
version=$(dpkg-query -W -f='${source:Version}' libimgui-dev)
imgui=build-web/imgui-$version
if [ ! -f "$imgui/imgui.cpp" ]; then
  apt=$PWD/build-web/apt
  rm -rf "$apt"
  mkdir -p "$apt/lists/partial" "$apt/sources" "$apt/download"
  # deb-src entries for the machine's own deb entries (deb822 files and sources.list lines).
  for file in /etc/apt/sources.list.d/*.sources; do
    [ -f "$file" ] && sed 's/^Types:.*/Types: deb-src/' "$file" > "$apt/sources/$(basename "$file")"
  done
  for file in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
    [ -f "$file" ] && { grep '^deb ' "$file" | sed 's/^deb /deb-src /' > "$apt/sources/$(basename "$file").list" || true; }
  done
  options=(-o "Dir::Etc::sourcelist=/dev/null" -o "Dir::Etc::sourceparts=$apt/sources" -o "Dir::State::Lists=$apt/lists")
  $sudo apt-get -qq "${options[@]}" update
  (cd "$apt/download" && $sudo apt-get -qq "${options[@]}" source "imgui=$version")
  rm -rf "$imgui"
  mv "$apt/download/imgui-${version%-*}" "$imgui"
  rm -rf "$apt"
fi

launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
# -fexceptions: the demo's errors (a bad scene, a bad value) are exceptions
# caught and shown; without it em++ aborts on the first throw.
emcmake cmake -S . -B build-web -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" \
  -DCMAKE_CXX_FLAGS=-fexceptions -DPARTICLES_IMGUI_SOURCE="$PWD/$imgui" \
  -DPARTICLES_BUILD_TESTS=OFF -DPARTICLES_BUILD_BENCHMARKS=OFF -DPARTICLES_INSTALL=OFF >/dev/null
cmake --build build-web -j"$(nproc)" --target particle-demo
ls -l build-web/particle-demo.html build-web/particle-demo.js build-web/particle-demo.wasm
