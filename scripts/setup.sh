#!/usr/bin/env bash
# Installs what meterstick needs on this machine, idempotently:
#   - qemu-system-arm (Debian package) for the firmware runs;
#   - chromium and chromium-driver (Debian packages) for the browser test of the page;
#   - the Cortex-M targets thumbv7em-none-eabihf (M4F), thumbv6m-none-eabi (M0/M0+) and
#     thumbv8m.main-none-eabihf (M33F), and wasm32-unknown-unknown for the page:
#       1. the idiomatic way, `rustup target add` (the machine's rustup toolchain);
#       2. when rustup is missing or cannot download, Debian's toolchain with the std
#          sources (rustc-web, cargo-web, rust-web-src, rust-web-llvm, lld-22), which
#          builds `core` itself (`-Z build-std=core`).
#   - the Picos' .uf2 converter, tools/uf2 (elf2flash-core from crates.io), built with the host
#     cargo into target/tools/;
#   - the declared MSRV toolchain (`rust-version` in Cargo.toml; rustup's minimal profile),
#     which scripts/test.sh checks the library crates with;
#   - Node.js and npm (Debian packages) and tests/pico's node_modules (`npm ci`: rp2040js, the
#     emulated RP2040 of scripts/pico-emu.sh).
# Writes the chosen mode to target/meterstick-toolchain.env for scripts/lib.sh.
# Set MS_CROSS=debian to force the fallback, MS_CROSS=rustup to forbid it.
# As root it installs what is missing; otherwise it stops with the exact command to run.
set -euo pipefail
cd "$(dirname "$0")/.."

TARGETS=(thumbv7em-none-eabihf thumbv6m-none-eabi thumbv8m.main-none-eabihf wasm32-unknown-unknown)
DEBIAN_RUST=(rustc-web cargo-web rust-web-src rust-web-llvm lld-22)
APT_UPDATED=0

say() { printf 'setup: %s\n' "$*" >&2; }

apt_install() {
  if [ "$(id -u)" != 0 ]; then
    say "missing: $*"
    say "run as root:  apt-get update && apt-get install -y --no-install-recommends $*"
    exit 1
  fi
  if [ "$APT_UPDATED" = 0 ]; then
    say "apt-get update"
    DEBIAN_FRONTEND=noninteractive apt-get update -qq >/dev/null
    APT_UPDATED=1
  fi
  say "apt-get install $*"
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "$@" >/dev/null
}

# --- QEMU --------------------------------------------------------------------------------
if ! command -v qemu-system-arm >/dev/null 2>&1; then
  apt_install qemu-system-arm
fi

# --- headless Chromium and its WebDriver (the browser test) -------------------------------
if ! command -v chromium >/dev/null 2>&1 || ! command -v chromedriver >/dev/null 2>&1; then
  apt_install chromium chromium-driver
fi

# --- host toolchain -----------------------------------------------------------------------
if ! command -v cargo >/dev/null 2>&1 && [ ! -x /usr/bin/cargo ]; then
  say "no cargo on PATH and no rustup: installing Debian's Rust toolchain"
  apt_install "${DEBIAN_RUST[@]}"
fi

# --- Cortex-M and wasm targets ------------------------------------------------------------
mode=""
want=${MS_CROSS:-auto}
if [ "$want" != debian ] && command -v rustup >/dev/null 2>&1; then
  installed=$(rustup target list --installed 2>/dev/null || true)
  missing=()
  for t in "${TARGETS[@]}"; do grep -qx "$t" <<<"$installed" || missing+=("$t"); done
  if [ ${#missing[@]} -eq 0 ]; then
    mode=rustup
  else
    say "rustup target add ${missing[*]}"
    if timeout 300 rustup target add "${missing[@]}" >&2; then
      mode=rustup
    else
      say "rustup could not add the targets; falling back to Debian's toolchain"
    fi
  fi
fi
if [ -z "$mode" ]; then
  if [ "$want" = rustup ]; then say "MS_CROSS=rustup but rustup cannot provide the targets"; exit 1; fi
  need=()
  [ -x /usr/bin/rustc ] && [ -x /usr/bin/cargo ] || need+=(rustc-web cargo-web)
  sysroot=$( [ -x /usr/bin/rustc ] && /usr/bin/rustc --print sysroot || echo /usr)
  [ -d "$sysroot/lib/rustlib/src/rust/library/core" ] || need+=(rust-web-src)
  dpkg -s rust-web-llvm >/dev/null 2>&1 || need+=(rust-web-llvm)
  dpkg -s lld-22 >/dev/null 2>&1 || need+=(lld-22)
  if [ ${#need[@]} -gt 0 ]; then apt_install "${need[@]}"; fi
  mode=debian
fi

# --- the declared MSRV (the workspace's rust-version), for scripts/test.sh's check ---------
# Only with rustup (about 10 s and 70 MB for the minimal profile); the Debian fallback has one
# compiler and skips the check.
msrv=$(sed -n 's/^rust-version = "\(.*\)"$/\1/p' Cargo.toml)
msrv_toolchain=""
if [ "$mode" = rustup ] && [ -n "$msrv" ]; then
  if rustup run "$msrv" rustc --version >/dev/null 2>&1; then
    msrv_toolchain=$msrv
  else
    say "rustup toolchain install $msrv --profile minimal (the declared MSRV)"
    if timeout 300 rustup toolchain install "$msrv" --profile minimal >&2; then
      msrv_toolchain=$msrv
    else
      say "rustup could not install $msrv: the MSRV check will be skipped"
    fi
  fi
fi

# --- the Picos' .uf2 converter -------------------------------------------------------------
# A host tool of its own workspace (tools/uf2); cargo skips it when it is up to date.
if command -v cargo >/dev/null 2>&1; then host_cargo=cargo; else host_cargo=/usr/bin/cargo; fi
"$host_cargo" build --quiet --locked --release --manifest-path tools/uf2/Cargo.toml --target-dir target/tools >&2

# --- the emulated Pico (tests/pico: rp2040js, pinned in its package-lock.json) ---------------
# Node.js runs the harness (scripts/pico-emu.sh); `npm ci` installs exactly the locked packages,
# again only when package-lock.json is newer than node_modules.
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  apt_install nodejs npm
fi
if [ ! -d tests/pico/node_modules ] || [ tests/pico/package-lock.json -nt tests/pico/node_modules ]; then
  say "npm ci (tests/pico)"
  (cd tests/pico && npm ci --no-audit --no-fund --loglevel=error >&2)
  touch tests/pico/node_modules
fi

mkdir -p target
{
  echo "MS_CROSS_MODE=$mode"
  echo "MS_MSRV_TOOLCHAIN=$msrv_toolchain"
} > target/meterstick-toolchain.env
say "cross toolchain: $mode ($(if [ "$mode" = debian ]; then /usr/bin/rustc --version; else rustc --version; fi))"
