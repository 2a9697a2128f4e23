#!/usr/bin/env python3
"""Times `legacy-rt grade` on a class made by bench/class.py against the shell loop it
replaces, `legacy-rt compare --diagnose` over the same pairs, one pair at a time. Prints
the CPU time (user + system of the processes) and the wall time of each, and their ratio.
The loop is run over the first --loop-students students only (it is the slow one), and
grade over those students alone, so that the ratio is measured on the same pairs, not
extrapolated; grade is then timed over the whole class.

    bench/grade.py --class /tmp/class [--threads 2] [--loop-students 20]
"""
import argparse, os, resource, subprocess, tempfile, time

import built


def cpu_seconds():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def timed(command, **kwargs):
    before, start = cpu_seconds(), time.monotonic()
    with open(os.devnull, "wb") as sink:  # write-only: see bench/alternate.py
        subprocess.run(command, check=False, stdout=sink, stderr=sink, **kwargs)
    return cpu_seconds() - before, time.monotonic() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--class", dest="folder", required=True)
    parser.add_argument("--binary", default=None, help="default: the release build (bench/built.py)")
    parser.add_argument("--threads", type=int, default=0)
    parser.add_argument("--loop-students", type=int, default=20)
    args = parser.parse_args()
    if args.binary is None:
        args.binary = built.built("release")
    binary = os.path.abspath(args.binary)
    scenes = os.path.join(args.folder, "scenes")
    subs = os.path.join(args.folder, "submissions")
    students = sorted(os.listdir(subs))
    names = sorted(f[:-4] for f in os.listdir(scenes) if f.endswith(".txt"))
    with tempfile.TemporaryDirectory() as scratch:
        # The same pairs for both: the first students, in a class of their own.
        few = os.path.join(scratch, "few")
        os.makedirs(few)
        for student in students[: args.loop_students]:
            os.symlink(os.path.abspath(os.path.join(subs, student)), os.path.join(few, student))
        threads = ["--threads", str(args.threads)]
        grade_few = timed([binary, "grade", *threads, scenes, few, "-o", os.path.join(scratch, "r1")])
        before, start = cpu_seconds(), time.monotonic()
        for student in students[: args.loop_students]:
            for name in names:
                image = os.path.join(subs, student, name + ".ppm")
                if os.path.exists(image):
                    # As the shell loop writes each report to a file.
                    with open(os.path.join(scratch, "report.json"), "wb") as out:
                        subprocess.run([binary, "compare", "--diagnose", "--threads", "1", "--json",
                                        os.path.join(scenes, name + ".txt"), image],
                                       stdout=out, stderr=subprocess.DEVNULL, check=False)
        loop = (cpu_seconds() - before, time.monotonic() - start)
        grade_all = timed([binary, "grade", *threads, scenes, subs, "-o", os.path.join(scratch, "r2")])
    pairs_few = min(args.loop_students, len(students)) * len(names)
    print(f"same {pairs_few} pairs ({min(args.loop_students, len(students))} students x {len(names)} scenes):")
    print(f"  compare --diagnose loop: {loop[0]:.1f} s CPU, {loop[1]:.1f} s wall")
    print(f"  grade:                   {grade_few[0]:.1f} s CPU, {grade_few[1]:.1f} s wall")
    print(f"  the loop takes {loop[0] / grade_few[0]:.2f}x grade's CPU time")
    print(f"whole class ({len(students)} students x {len(names)} scenes = {len(students) * len(names)} pairs):")
    print(f"  grade: {grade_all[0]:.1f} s CPU, {grade_all[1]:.1f} s wall")


if __name__ == "__main__":
    main()
