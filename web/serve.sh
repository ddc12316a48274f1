#!/usr/bin/env bash
# Serves the page on http://127.0.0.1:${PORT:-8000}/; it plans the default job (paper 004's lens
# array) on load. Builds pkg/ first only when it is missing (it is committed).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/tools.sh"
if [ ! -f "$root/pkg/spiralcam_web_bg.wasm" ]; then
  "$root/web/build.sh"
fi
exec python3 "$root/web/serve.py" "${PORT:-8000}"
