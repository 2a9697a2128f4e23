#!/usr/bin/env bash
# legacy-rt against POV-Ray 3.7, side by side (issue 6). For each scene of bench/ it
# renders the legacy file with legacy-rt and the .pov twin with POV-Ray, both at
# 1600x1200 on one thread, one ray per pixel, shadows on, no anti-aliasing, and prints
# the median times (hyperfine, several runs each) and their ratio.
#
#   bench/compare.sh            (installs povray and hyperfine with apt when missing)
#   RUNS=10 bench/compare.sh    more runs per command
#
# The scenes: the course scene spec1, examples/quadrics_gallery.txt, and the generated
# 1 000-object scene of tests/support/generated.rs. Each .pov file lists the
# differences that remain; the lighting models differ, so this compares work, not
# colours.
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS="${RUNS:-5}"
WIDTH=1600
HEIGHT=1200

if ! command -v povray >/dev/null || ! command -v hyperfine >/dev/null; then
    echo "installing povray and hyperfine with apt-get" >&2
    SUDO=""
    if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
    $SUDO apt-get update -q >&2
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q povray hyperfine >&2
fi

cargo build --release --locked --bin legacy-rt >&2
out="target/bench"
mkdir -p "$out"
cargo run --release --locked -q --example scaling -- --scene 1000 > "$out/many.txt"

course="../shared/course-scenes/spec1.txt"
if [ ! -f "$course" ]; then
    echo "missing $course (the course scenes beside the repository)" >&2
    exit 1
fi

printf '%-10s %12s %12s %8s\n' scene legacy-rt povray ratio
for pair in "spec1:$course" "gallery:examples/quadrics_gallery.txt" "many:$out/many.txt"; do
    name="${pair%%:*}"
    legacy="${pair#*:}"
    # POV-Ray writes its image into the current folder (its default file-access policy
    # allows that); +WT1 one thread, -A no anti-aliasing, -D no display, -GA quiet.
    hyperfine --style none --warmup 1 --runs "$RUNS" --export-json "$out/$name.json" \
        -n legacy-rt "target/release/legacy-rt $WIDTH $HEIGHT < $legacy > $out/$name.ppm" \
        -n povray "cd $out && povray +I../../bench/$name.pov +O$name-pov.png +W$WIDTH +H$HEIGHT +WT1 -A -D -GA" \
        >&2
    python3 - "$out/$name.json" "$name" <<'PY'
import json, sys
results = {r["command"]: r["median"] for r in json.load(open(sys.argv[1]))["results"]}
legacy, povray = results["legacy-rt"], results["povray"]
print(f"{sys.argv[2]:<10} {legacy:11.3f}s {povray:11.3f}s {povray / legacy:7.2f}x")
PY
done
