#!/usr/bin/env python3
"""Writes the scene of bench/load.sh into the file given: one light and 999,999 small
spheres at random (seed 1) in front of the eye, 1,000,000 records (about 52 MB), the
most a scene may hold."""
import random, sys

args = sys.argv[1:]
# An option is never a file name: --help prints this, anything else is refused.
if args[:1] in (["-h"], ["--help"]):
    print(__doc__)
    sys.exit(0)
if len(args) != 1 or args[0].startswith("-"):
    sys.exit(__doc__ + "\n\nusage: bench/million.py FILE")
random.seed(1)
with open(args[0], "w") as f:
    f.write("8 6   world\n0 0 3   viewpoint\n10\n9 9 9\n0 4 2\n")
    for _ in range(999_999):
        x, y, z = random.uniform(-40, 40), random.uniform(-30, 30), random.uniform(-200, -10)
        f.write(f"13\n1 0.5 0.5\n2 2 2\n0 0 0\n{x:.3f} {y:.3f} {z:.3f}\n0.2\n")
