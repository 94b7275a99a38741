#!/usr/bin/env bash
# The page: builds the core for the browser (web/page/pkg/meterstick_web*.wasm) and serves
# web/page on http://127.0.0.1:8000/ with `host-sim serve` (arguments go to it: --port N,
# --replay out/run). `--build` only builds.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
. scripts/lib.sh
wasm=$(build_web)
for module in "${WEB_MODULES[@]}"; do printf 'web: %s (%s bytes)\n' "${module#"$ROOT"/}" "$(stat -c %s "$module")"; done
if [ "${1:-}" = --build ]; then exit 0; fi
exec $HOST_CARGO run --locked --release -p meterstick-host-sim -- serve "$@"
