#!/usr/bin/env bash
# Builds the web page into web/dist/: the library compiled to WebAssembly with its
# JavaScript binding (wasm-bindgen), the page's HTML, CSS and JavaScript, and the
# project's example scenes. dist/ is a folder of static files: any static server can
# serve it (web/serve.sh uses Python's), and copying it to a static host publishes it.
#
# It installs what it needs when missing: the wasm32-unknown-unknown target (rustup) and
# the wasm-bindgen command of the version web/wasm/Cargo.toml pins (cargo install).
set -euo pipefail
web="$(cd "$(dirname "$0")" && pwd)"
cd "$web"

if ! rustup target list --installed | grep -qx wasm32-unknown-unknown; then
  echo "build.sh: adding the Rust target wasm32-unknown-unknown" >&2
  rustup target add wasm32-unknown-unknown
fi

# The command must be the crate's version: the crate pins it with `=`.
version=$(sed -n 's/^wasm-bindgen = "=\(.*\)"$/\1/p' wasm/Cargo.toml)
if [ "$(wasm-bindgen --version 2>/dev/null)" != "wasm-bindgen $version" ]; then
  echo "build.sh: installing wasm-bindgen-cli $version (a few minutes, once)" >&2
  # With its own lock file first; a registry mirror may lack a locked version, and then
  # the newest compatible versions are taken.
  cargo install wasm-bindgen-cli --version "$version" --locked ||
    cargo install wasm-bindgen-cli --version "$version"
fi

# Where cargo puts the .wasm depends on CARGO_TARGET_DIR and the configuration: ask it,
# from the build's own list of artifacts.
wasm=$(cargo build --release --locked --target wasm32-unknown-unknown \
  --manifest-path wasm/Cargo.toml --message-format=json-render-diagnostics |
  python3 -c '
import json, sys
for line in sys.stdin:
    try:
        message = json.loads(line)
    except ValueError:
        continue
    if message.get("reason") == "compiler-artifact":
        for name in message.get("filenames", []):
            if name.endswith(".wasm"):
                print(name)
' | tail -n 1)
if [ -z "$wasm" ] || [ ! -f "$wasm" ]; then
  echo "build.sh: cargo built no .wasm for web/wasm" >&2
  exit 1
fi

rm -rf dist
mkdir -p dist/examples/textures
wasm-bindgen --target web --no-typescript --out-dir dist/pkg "$wasm"
cp index.html style.css app.js worker.js dist/
cp ../examples/*.txt dist/examples/
cp ../examples/textures/*.ppm dist/examples/textures/
# The docs that the library's messages name (docs/scene-format.md, ...): the page links
# them, as the text they are.
mkdir -p dist/docs
cp ../docs/*.md dist/docs/
python3 - <<'PY'
import json, os
scenes = sorted(f for f in os.listdir("dist/examples") if f.endswith(".txt"))
textures = sorted(os.listdir("dist/examples/textures"))
with open("dist/examples/index.json", "w") as out:
    json.dump({"scenes": scenes, "textures": textures}, out, indent=1)
PY
echo "build.sh: the page is in web/dist/ ($(du -sh dist | cut -f1))" >&2
