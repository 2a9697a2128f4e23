#!/usr/bin/env bash
# The figures of issue 47, for a quiet machine (nothing else running): legacy-rt against
# Tachyon on the twins of bench/tachyon_twins.py, on one thread and on every core, and a
# million spheres (bench/million.py) read and rendered on 1, 2 and every core. Every
# group of commands is alternated run by run (bench/alternate.py): CPU-time medians for
# one thread, wall-clock medians for several.
#
#   bench/quiet.sh [BINARY]        a built legacy-rt (default: cargo's release build)
#   OLD=BINARY bench/quiet.sh      also time another build, beside it in each group
#   TACHYON=PATH THREADS=N RUNS=N  Tachyon's command (default tachyon), the threads of
#                                  the "every core" runs (default nproc), runs per group
#
# Needs python3 and Tachyon (Debian's package tachyon); spec1 is read from COURSE
# (default ../shared/course-scenes) when it is there. Writes its scenes and images to
# target/quiet.
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS="${RUNS:-5}"
THREADS="${THREADS:-$(nproc)}"
TACHYON="${TACHYON:-tachyon}"
binary="${1:-}"
if [ -z "$binary" ]; then
    cargo build --release --locked --bin legacy-rt >&2
    binary="$(python3 bench/built.py release)"
fi
out="target/quiet"
mkdir -p "$out"
python3 bench/tachyon_twins.py "$out" > /dev/null
[ -f "$out/million.txt" ] || python3 bench/million.py "$out/million.txt"

# NAME=COMMAND for legacy-rt, and for OLD if given; ARGS after the binary.
ours() {
    local name="$1"; shift
    echo "$name=$binary $*"
    if [ -n "${OLD:-}" ]; then echo "$name-old=$OLD $*"; fi
}
tachyon() {
    echo "tachyon-$1=$TACHYON $out/$2.dat -res $3 $4 -numthreads $1 -aasamples 0 -fullshade -format PPM -o $out/$2-tachyon.ppm"
}

echo "machine: $(nproc) cores, $(uname -m), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
echo
echo "One thread, 1600x1200: CPU seconds, medians of $RUNS runs alternated run by run"
for twin in twin_small twin_many twin_grid; do
    echo "$twin"
    mapfile -t commands < <(ours legacy-rt "1600 1200 < $out/$twin.txt > $out/$twin.ppm"; tachyon 1 "$twin" 1600 1200)
    python3 bench/alternate.py --runs "$RUNS" "${commands[@]}"
done

echo
echo "Threads: wall seconds, medians of 3 runs alternated, 1 and $THREADS threads"
scenes="twin_many:$out/twin_many.txt"
spec1="${COURSE:-../shared/course-scenes}/spec1.txt"
if [ -f "$spec1" ]; then
    scenes="spec1:$spec1 $scenes"
fi
for pair in $scenes; do
    name="${pair%%:*}"; scene="${pair#*:}"
    for size in "1600 1200" "3200 2400"; do
        echo "$name at ${size/ /x}"
        mapfile -t commands < <(
            ours "t1" "--threads 1 $size < $scene > $out/$name.ppm"
            ours "t$THREADS" "--threads $THREADS $size < $scene > $out/$name.ppm"
            if [ "$name" = twin_many ]; then tachyon 1 twin_many $size; tachyon "$THREADS" twin_many $size; fi)
        python3 bench/alternate.py --runs 3 --wall "${commands[@]}"
    done
done

echo
echo "A million spheres (bench/million.py) at 640x480: wall seconds, medians of 3 runs alternated"
mapfile -t commands < <(for t in 1 2 "$THREADS"; do ours "t$t" "--threads $t 640 480 < $out/million.txt > $out/million.ppm"; done)
python3 bench/alternate.py --runs 3 --wall "${commands[@]}"
echo "loading alone (2x2)"
mapfile -t commands < <(for t in 1 2 "$THREADS"; do ours "t$t" "--threads $t 2 2 < $out/million.txt > $out/million-2x2.ppm"; done)
python3 bench/alternate.py --runs 3 --wall "${commands[@]}"
