# Tool installers shared by web/build.sh, web/serve.sh and tests/run.sh (sourced, not run).
# Each installs what is missing on a fresh machine and does nothing when it is already there.

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
WASM_BINDGEN_VERSION=0.2.130

say() { printf '\033[1m== %s\033[0m\n' "$*" >&2; }

# The Rust toolchain pinned in rust-toolchain.toml, with rustfmt, clippy and the wasm32 target.
ensure_rust() {
  local channel
  channel="$(sed -n 's/^channel *= *"\(.*\)"/\1/p' "$root/rust-toolchain.toml")"
  if ! rustup target list --installed --toolchain "$channel" 2>/dev/null | grep -qx wasm32-unknown-unknown \
    || ! rustup component list --installed --toolchain "$channel" 2>/dev/null | grep -q '^clippy'; then
    say "installing Rust $channel with clippy, rustfmt and wasm32-unknown-unknown"
    rustup toolchain install "$channel" --profile minimal --component rustfmt,clippy --target wasm32-unknown-unknown
  fi
}

# wasm-bindgen CLI of the same version as the wasm-bindgen crate.
ensure_wasm_bindgen() {
  if [ "$(wasm-bindgen --version 2>/dev/null)" != "wasm-bindgen $WASM_BINDGEN_VERSION" ]; then
    say "installing wasm-bindgen-cli $WASM_BINDGEN_VERSION (about 5 minutes)"
    cargo install wasm-bindgen-cli --version "$WASM_BINDGEN_VERSION"
  fi
}

apt_updated=
# ensure_apt COMMAND PACKAGE...: installs the Debian packages when COMMAND is missing.
ensure_apt() {
  local cmd="$1"
  shift
  command -v "$cmd" >/dev/null 2>&1 && return 0
  local sudo=
  [ "$(id -u)" = 0 ] || sudo=sudo
  if [ -z "$apt_updated" ]; then
    say "apt-get update"
    $sudo apt-get update -qq
    apt_updated=1
  fi
  say "installing $*"
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "$@" >/dev/null
}

# ensure_npm DIR: the Node packages of DIR's package-lock.json.
ensure_npm() {
  local dir="$1"
  if [ ! -d "$dir/node_modules" ] || [ "$dir/package-lock.json" -nt "$dir/node_modules/.package-lock.json" ]; then
    say "npm ci in $dir"
    (cd "$dir" && npm ci --no-audit --no-fund --loglevel=error)
  fi
}
