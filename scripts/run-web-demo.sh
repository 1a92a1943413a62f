#!/usr/bin/env bash
# Builds the demo's web page (scripts/build-web.sh) and serves build-web/ on
# http://127.0.0.1:8000/ (PORT=N for another port). The desktop's options go
# in the URL's query: http://127.0.0.1:8000/?scene=hair&integrator=rk4&dt=0.001
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build-web.sh
port=${PORT:-8000}
echo "particle-demo: http://127.0.0.1:$port/ (Ctrl-C stops the server)"
exec python3 -m http.server --bind 127.0.0.1 --directory build-web "$port"
