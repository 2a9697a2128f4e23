#!/usr/bin/env python3
"""Compares two legacy-rt binaries on the render bench's scenes: the programs alternate
run by run (so that load on a shared machine hits both alike), each run's CPU time
(user + system, of the child) is taken, and the medians and their ratio are printed.
Both binaries must give the same bytes; the script says so or stops.

    bench/ab.py OLD NEW [--runs 7] [--size 1024x768]

Run it from the repository; the course scenes are read from ../shared/course-scenes.
"""
import os, resource, statistics, subprocess, sys

def main():
    args = sys.argv[1:]
    runs, size = 7, "1024x768"
    if "--runs" in args:
        i = args.index("--runs"); runs = int(args[i + 1]); del args[i:i + 2]
    if "--size" in args:
        i = args.index("--size"); size = args[i + 1]; del args[i:i + 2]
    if len(args) != 2:
        sys.exit(__doc__)
    old, new = args
    width, height = size.split("x")
    scenes = ["../shared/course-scenes/spec1.txt", "../shared/course-scenes/a04.txt",
              "../shared/course-scenes/d04.txt", "examples/quadrics_gallery.txt"]
    print(f"{size}, one thread, {runs} alternated runs each, median CPU seconds")
    print(f"{'scene':<22} {'old':>8} {'new':>8} {'new/old':>8}")
    for scene in scenes:
        if not os.path.exists(scene):
            print(f"{scene:<22} skipped: absent"); continue
        text = open(scene, "rb").read()
        times = {old: [], new: []}
        outputs = {}
        for _ in range(runs):
            for binary in (old, new):
                before = resource.getrusage(resource.RUSAGE_CHILDREN)
                out = subprocess.run([binary, width, height], input=text,
                                     capture_output=True, check=True).stdout
                after = resource.getrusage(resource.RUSAGE_CHILDREN)
                cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
                times[binary].append(cpu)
                outputs[binary] = out
        if outputs[old] != outputs[new]:
            sys.exit(f"{scene}: the two binaries give different bytes")
        a, b = statistics.median(times[old]), statistics.median(times[new])
        print(f"{os.path.basename(scene):<22} {a:8.3f} {b:8.3f} {b / a:8.3f}")

main()
