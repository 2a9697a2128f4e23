#!/usr/bin/env python3
"""Makes a class to grade: SCENES/ (copies of the scene files given) and SUBMISSIONS/,
one folder per student with an image of every scene, as students hand them in. Each
student's image of a scene is, by a fixed pseudo-random draw (the same class for the same
arguments): the reference (60 %), a render with one of the catalogued mistakes (25 %:
no-shadows, square-falloff, upside-down, nearer-root, no-z-rule), a single-precision
textbook tracer's (10 %), missing or garbage (5 %). Each kind of image is rendered once
per scene and hard-linked into the students' folders, so a class of 300 students costs
the renders of a few images per scene and little disk.

    bench/class.py --students 300 --size 640 480 --out /tmp/class SCENE.txt...

Then time `legacy-rt grade` against a loop of `legacy-rt compare --diagnose` over the
same pairs with bench/grade.py.
"""
import argparse, os, random, shutil, subprocess, sys

import built

KINDS = [
    ("reference", [], 60),
    ("no-shadows", ["--variant", "no-shadows"], 5),
    ("square-falloff", ["--variant", "square-falloff"], 5),
    ("upside-down", ["--variant", "upside-down"], 5),
    ("nearer-root", ["--variant", "nearer-root"], 5),
    ("no-z-rule", ["--variant", "no-z-rule"], 5),
    ("textbook-f32", ["--kernel", "textbook-f32"], 10),
    ("missing", None, 3),
    ("garbage", None, 2),
]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--students", type=int, default=300)
    parser.add_argument("--size", type=int, nargs=2, default=[640, 480])
    parser.add_argument("--out", required=True)
    parser.add_argument("--binary", default=None, help="default: the release build (bench/built.py)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("scenes", nargs="+")
    args = parser.parse_args()
    if args.binary is None:
        args.binary = built.built("release")
    if os.path.exists(args.out):
        sys.exit(f"{args.out} exists: give a new folder")
    scenes_dir = os.path.join(args.out, "scenes")
    kinds_dir = os.path.join(args.out, "kinds")
    subs_dir = os.path.join(args.out, "submissions")
    for folder in (scenes_dir, kinds_dir, subs_dir):
        os.makedirs(folder)
    w, h = (str(n) for n in args.size)
    names = []
    for path in args.scenes:
        name = os.path.splitext(os.path.basename(path))[0]
        names.append(name)
        shutil.copy(path, os.path.join(scenes_dir, name + ".txt"))
        for kind, flags, _ in KINDS:
            out = os.path.join(kinds_dir, f"{name}-{kind}.ppm")
            if kind == "garbage":
                with open(out, "wb") as f:
                    f.write(b"P6 640 480 255\n" + b"\x00" * 1000)  # truncated
            elif flags is not None:
                with open(path, "rb") as scene:
                    subprocess.run([args.binary, w, h, *flags, "-o", out], stdin=scene, check=True)
    draw = random.Random(args.seed)
    weights = [weight for _, _, weight in KINDS]
    counts = {kind: 0 for kind, _, _ in KINDS}
    for s in range(args.students):
        folder = os.path.join(subs_dir, f"student{s:04d}")
        os.makedirs(folder)
        for name in names:
            kind = draw.choices(KINDS, weights)[0][0]
            counts[kind] += 1
            if kind != "missing":
                os.link(os.path.join(kinds_dir, f"{name}-{kind}.ppm"), os.path.join(folder, name + ".ppm"))
    print(f"{args.students} students x {len(names)} scenes at {w}x{h} in {args.out}:",
          ", ".join(f"{n} {k}" for k, n in counts.items()))


if __name__ == "__main__":
    main()
