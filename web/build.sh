#!/usr/bin/env bash
# Builds the page's WebAssembly package into pkg/ (or the folder given as $1) from the
# committed source. The build is reproducible: absolute paths of this checkout, of the Cargo
# home and of the toolchain are remapped, the dependency versions come from Cargo.lock, and
# wasm-bindgen is pinned, so the same source gives the same bytes on any machine.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/tools.sh"
out="${1:-$root/pkg}"
ensure_rust
ensure_wasm_bindgen

cd "$root"
cargo_home="$(cd "${CARGO_HOME:-$HOME/.cargo}" && pwd)"
sysroot="$(rustc --print sysroot)"
sep=$'\x1f'
export CARGO_ENCODED_RUSTFLAGS="--remap-path-prefix=$root=/spiralcam${sep}--remap-path-prefix=$cargo_home=/cargo${sep}--remap-path-prefix=$sysroot=/rust"
export CARGO_TARGET_DIR="$root/target/pkg-build"
say "cargo build spiralcam-web (wasm32, release)"
cargo build --locked -p spiralcam-web --release --target wasm32-unknown-unknown

say "wasm-bindgen → $out"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
wasm-bindgen --target web --out-dir "$tmp" "$CARGO_TARGET_DIR/wasm32-unknown-unknown/release/spiralcam_web.wasm"
mkdir -p "$out"
rm -f "$out"/spiralcam_web*
cp "$tmp"/* "$out"/
ls -l "$out" >&2
