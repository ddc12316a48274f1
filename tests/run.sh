#!/usr/bin/env bash
# Runs every test of spiralcam, exactly what CI runs (.ci/run calls this and nothing else).
# On a fresh machine it first installs what is missing: the pinned Rust toolchain with the
# wasm32 target, wasm-bindgen-cli, Chromium, LinuxCNC's rs274 interpreter and the Node packages
# of the browser tests. Then: formatting, clippy (native and wasm32), the workspace tests,
# rustdoc without warnings, a fresh build of pkg/ compared with the committed pkg/, and the
# browser tests in headless Chromium (WebGPU and WebGL2).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../web/tools.sh"
cd "$root"

ensure_rust
ensure_wasm_bindgen
ensure_apt rs274 linuxcnc-uspace
ensure_apt chromium chromium
ensure_npm "$root/tests/browser"

say "cargo fmt --check"
cargo fmt --all -- --check

say "clippy (native)"
cargo clippy --locked --workspace --all-targets -- -D warnings

say "clippy (wasm32)"
cargo clippy --locked -p spiralcam -p spiralcam-web --target wasm32-unknown-unknown -- -D warnings

say "cargo test"
cargo test --locked --workspace

say "cargo doc"
RUSTDOCFLAGS="-D warnings" cargo doc --locked --workspace --no-deps

say "pkg/ is what web/build.sh makes of this source"
fresh="$(mktemp -d)"
trap 'rm -rf "$fresh"' EXIT
"$root/web/build.sh" "$fresh"
if ! diff -r "$root/pkg" "$fresh"; then
  echo "pkg/ differs from a fresh build: run web/build.sh and commit pkg/" >&2
  exit 1
fi

say "the command line the browser tests compare with (cli-test profile)"
cargo build --locked -p spiralcam --bin spiralcam --profile cli-test

say "browser tests"
(cd "$root/tests/browser" && node --test --test-concurrency=1 --test-reporter=spec)

say "all tests passed"
