#!/usr/bin/env bash
# No reachable panic in meterstick-link: link a Cortex-M binary that uses all of it with a
# panic handler calling an undefined symbol, for the M4F and the M0, at the firmware's
# opt-level ("s") and at 3. Usage: bash check.sh [cargo target dir]
set -euo pipefail
cd "$(dirname "$0")"
target_dir="${1:-target}"
for target in thumbv7em-none-eabihf thumbv6m-none-eabi; do
    for opt in s 3; do
        echo "== $target, opt-level $opt"
        CARGO_PROFILE_RELEASE_OPT_LEVEL="$opt" \
            cargo build --release --target "$target" --target-dir "$target_dir/$opt"
    done
done
echo "no panic path: ok"
