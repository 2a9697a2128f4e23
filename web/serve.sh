#!/usr/bin/env bash
# Builds the page (web/build.sh) and serves web/dist/ on http://localhost:PORT/ (8000
# unless given), until Ctrl-C.
set -euo pipefail
web="$(cd "$(dirname "$0")" && pwd)"
port="${1:-8000}"
"$web/build.sh"
echo "serving the page on http://localhost:$port/ (Ctrl-C stops)" >&2
exec python3 -m http.server "$port" --bind 127.0.0.1 --directory "$web/dist"
