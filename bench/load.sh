#!/usr/bin/env bash
# Loading at scale (issue 16): a generated scene of one light and 999,999 spheres
# (1,000,000 records, about 52 MB, the most a scene may hold), rendered at 2x2 so that
# the time is the loading's. Prints the median CPU time (user + system) and the largest
# peak memory of RUNS runs.
#
#   bench/load.sh            RUNS=5 by default
#   bench/load.sh OTHER-BINARY    the same for another build of legacy-rt
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS="${RUNS:-5}"
binary="${1:-$(python3 bench/built.py release)}"
if [ -z "${1:-}" ]; then cargo build --release --locked --bin legacy-rt >&2; fi
out="target/bench"
mkdir -p "$out"
scene="$out/million.txt"
if [ ! -f "$scene" ]; then
    python3 bench/million.py "$scene"
fi
python3 - "$binary" "$scene" "$RUNS" <<'PY'
import os, resource, statistics, subprocess, sys
binary, scene, runs = sys.argv[1], sys.argv[2], int(sys.argv[3])
times, peaks = [], []
for _ in range(runs):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    with open(scene, "rb") as stdin:
        # /dev/null for writing only: legacy-rt takes a read-write one (DEVNULL) for a
        # closed standard output.
        with open(os.devnull, "wb") as sink:
            subprocess.run([binary, "2", "2"], stdin=stdin, stdout=sink, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    times.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
    peaks.append(after.ru_maxrss)
size = os.path.getsize(scene) / 1e6
print(f"{scene}: {size:.1f} MB, 1,000,000 records")
print(f"CPU time median of {runs}: {statistics.median(times):.2f} s "
      f"({1e6 / statistics.median(times) / 1e6:.2f} M records/s); "
      f"peak memory {max(peaks) / 1024:.0f} MB")
PY
