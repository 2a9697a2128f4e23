#!/usr/bin/env bash
# legacy-rt against POV-Ray 3.7 (issue 6) and Tachyon (issue 16), side by side. For each
# scene it renders the legacy file with legacy-rt and its twin with the other program,
# both at 1600x1200 on one thread, one ray per pixel, shadows on, no anti-aliasing, the
# two alternated run by run, and prints the median CPU times and their ratio
# (bench/alternate.py).
#
#   bench/compare.sh            (installs povray and tachyon with apt when missing)
#   RUNS=10 bench/compare.sh    more runs per command
#
# The scenes: against POV-Ray, the course scene spec1, examples/quadrics_gallery.txt and
# the generated 1 000-object scene of tests/support/generated.rs (each .pov file lists
# the differences that remain); against Tachyon, the three twins that
# bench/tachyon_twins.py writes (7, 113 and 102 objects). The lighting models differ, so this
# compares work, not colours.
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS="${RUNS:-5}"
WIDTH=1600
HEIGHT=1200

if ! command -v povray >/dev/null || ! command -v tachyon >/dev/null; then
    echo "installing povray and tachyon with apt-get" >&2
    SUDO=""
    if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
    $SUDO apt-get update -q >&2
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q povray tachyon >&2
fi

cargo build --release --locked --bin legacy-rt >&2
# Where cargo put it (CARGO_TARGET_DIR or target/), and a folder for the bench's files.
binary="$(python3 bench/built.py release)"
out="$(dirname "$(dirname "$binary")")/bench"
mkdir -p "$out"
cargo run --release --locked -q --example scaling -- --scene 1000 > "$out/many.txt"

course="../shared/course-scenes/spec1.txt"
if [ ! -f "$course" ]; then
    echo "missing $course (the course scenes beside the repository)" >&2
    exit 1
fi

echo "CPU seconds, medians of $RUNS runs alternated run by run, one thread, ${WIDTH}x${HEIGHT}"
for pair in "spec1:$course" "gallery:examples/quadrics_gallery.txt" "many:$out/many.txt"; do
    name="${pair%%:*}"
    legacy="${pair#*:}"
    echo "$name (legacy-rt vs POV-Ray 3.7)"
    # POV-Ray writes its image into the current folder (its default file-access policy
    # allows that); +WT1 one thread, -A no anti-aliasing, -D no display, -GA quiet.
    python3 bench/alternate.py --runs "$RUNS" \
        "legacy-rt=$binary $WIDTH $HEIGHT < $legacy > $out/$name.ppm" \
        "povray=cd $out && povray +I$PWD/bench/$name.pov +O$name-pov.png +W$WIDTH +H$HEIGHT +WT1 -A -D -GA"
done

# Tachyon: the twins of bench/tachyon_twins.py, shadows on (-fullshade), no
# anti-aliasing, one thread.
python3 bench/tachyon_twins.py "$out"
for name in twin_small twin_many twin_grid; do
    echo "$name (legacy-rt vs Tachyon, bench/tachyon_twins.py)"
    python3 bench/alternate.py --runs "$RUNS" \
        "legacy-rt=$binary $WIDTH $HEIGHT < $out/$name.txt > $out/$name-twin.ppm" \
        "tachyon=tachyon $out/$name.dat -res $WIDTH $HEIGHT -numthreads 1 -aasamples 0 -fullshade -format PPM -o $out/$name-tachyon.ppm"
done
