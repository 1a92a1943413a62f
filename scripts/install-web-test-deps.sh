#!/usr/bin/env bash
# What the web tests (tests/web, label "web") need besides the page
# (scripts/build-web.sh): Chromium and npm from Debian's packages, and
# puppeteer-core at the version tests/web/package-lock.json pins, installed
# with npm into build/web-tests/node_modules (not the source tree).
set -euo pipefail
cd "$(dirname "$0")/.."
# npm comes with some builds of node (which then conflict with Debian's npm).
extra=(chromium)
command -v npm >/dev/null || extra+=(npm)
bash scripts/install-deps.sh "${extra[@]}"
modules=build/web-tests
mkdir -p "$modules"
if ! cmp -s tests/web/package-lock.json "$modules/package-lock.json" || [ ! -d "$modules/node_modules/puppeteer-core" ]; then
  cp tests/web/package.json tests/web/package-lock.json "$modules/"
  (cd "$modules" && npm ci --no-audit --no-fund --loglevel=error)
fi
