#!/usr/bin/env bash
# The web page's browser test: installs what it needs when missing (Debian's chromium,
# playwright-core from npm, and through web/build.sh the wasm32 target and wasm-bindgen),
# builds the page and the command line it is checked against, and runs
# web/test/e2e.mjs in headless chromium. Arguments go to e2e.mjs (--screenshot FILE,
# --bench).
set -euo pipefail
web="$(cd "$(dirname "$0")" && pwd)"
cd "$web/.."

if ! command -v chromium >/dev/null 2>&1; then
  if [ "$(id -u)" = 0 ]; then
    echo "test.sh: installing chromium (apt-get)" >&2
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null
  else
    echo "test.sh: the browser test needs Debian's chromium: sudo apt-get install chromium" >&2
    exit 1
  fi
fi
(cd web && npm ci --no-audit --no-fund --loglevel=error)
# Built with a target directory of its own, as a user's CARGO_TARGET_DIR may be: the
# script asks cargo where the .wasm went (it once read a fixed path).
CARGO_TARGET_DIR="$web/wasm/target/elsewhere" web/build.sh
# The command line the page must agree with, the debug build: built as
# `cargo test` builds it (the same features), so that after `cargo test` this is no work.
cargo test --locked --no-run
if [[ " $* " == *" --bench "* ]]; then
  cargo build --locked --release --bin legacy-rt
fi
# Where cargo put them: target/ or the user's CARGO_TARGET_DIR.
export LEGACY_RT="${LEGACY_RT:-$(python3 bench/built.py debug)}"
export LEGACY_RT_RELEASE="${LEGACY_RT_RELEASE:-$(python3 bench/built.py release)}"
node web/test/e2e.mjs "$@"
