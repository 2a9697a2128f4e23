#!/usr/bin/env python3
"""Runs shell commands in turn, run by run (A B C A B C ...), so that the load of a shared
machine falls on all of them alike, and prints each one's median CPU time (user + system
of its processes), or with --wall its median wall-clock time (for runs on several
threads), and its ratio to the first.

    bench/alternate.py [--runs 5] [--wall] NAME=COMMAND NAME=COMMAND ...
"""
import os, resource, statistics, subprocess, sys, time

def cpu_seconds():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime

def main():
    args = sys.argv[1:]
    runs = 5
    if args[:1] == ["--runs"]:
        runs, args = int(args[1]), args[2:]
    wall = args[:1] == ["--wall"]
    if wall:
        args = args[1:]
    clock = time.perf_counter if wall else cpu_seconds
    if not args or any("=" not in a for a in args):
        sys.exit(__doc__)
    commands = [a.split("=", 1) for a in args]
    times = {name: [] for name, _ in commands}
    # /dev/null opened for writing only: legacy-rt takes a read-write one (what
    # subprocess.DEVNULL opens) for a closed standard output, and refuses it.
    sink = open(os.devnull, "wb")
    for _ in range(runs):
        for name, command in commands:
            before = clock()
            subprocess.run(command, shell=True, check=True,
                           stdout=sink, stderr=sink)
            times[name].append(clock() - before)
    first = statistics.median(times[commands[0][0]])
    for name, _ in commands:
        median = statistics.median(times[name])
        kind = "wall" if wall else "CPU"
        print(f"  {name:<10} {median:8.3f} s {kind:<4} {median / first:6.2f}x the first")

if __name__ == "__main__":
    main()
