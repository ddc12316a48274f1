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
rm -f "$out"/spiralcam_web* "$out"/spiralcam.js "$out"/spiralcam.d.ts "$out"/spiralcam-worker.js "$out"/package.json
cp "$tmp"/* "$out"/
# The JavaScript API (README, "Use it from JavaScript") and the package's manifest, so pkg/ can
# be vendored or published as an npm package as it is.
cp "$root"/web/package/spiralcam.js "$root"/web/package/spiralcam-worker.js "$root"/web/package/spiralcam.d.ts "$out"/
version="$(sed -n 's/^version *= *"\(.*\)"/\1/p' "$root/Cargo.toml" | head -n 1)"
cat >"$out/package.json" <<JSON
{
  "name": "spiralcam",
  "version": "$version",
  "description": "Spiral tool paths for fast and slow tool servo diamond turning of freeform optics (WebAssembly)",
  "license": "MIT",
  "type": "module",
  "main": "./spiralcam.js",
  "module": "./spiralcam.js",
  "types": "./spiralcam.d.ts",
  "exports": {
    ".": { "types": "./spiralcam.d.ts", "default": "./spiralcam.js" },
    "./wasm": { "types": "./spiralcam_web.d.ts", "default": "./spiralcam_web.js" },
    "./spiralcam_web_bg.wasm": "./spiralcam_web_bg.wasm"
  },
  "files": ["spiralcam.js", "spiralcam.d.ts", "spiralcam-worker.js", "spiralcam_web.js", "spiralcam_web.d.ts", "spiralcam_web_bg.wasm", "spiralcam_web_bg.wasm.d.ts"],
  "sideEffects": false
}
JSON
ls -l "$out" >&2
