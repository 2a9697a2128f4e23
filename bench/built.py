#!/usr/bin/env python3
"""The path of the legacy-rt binary cargo builds, wherever the target folder is.

    bench/built.py [PROFILE]      prints it (PROFILE: release, the default, or debug)

cargo puts its builds under target/ unless CARGO_TARGET_DIR (or a .cargo/config) says
otherwise; `cargo metadata` knows where. The bench scripts and web/test.sh ask here
instead of assuming the default target folder.
"""

import json
import os
import subprocess
import sys


def built(profile="release"):
    """The binary of `profile` in this checkout's target folder (built or not)."""
    top = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    meta = subprocess.run(
        ["cargo", "metadata", "--format-version", "1", "--no-deps", "--offline"],
        capture_output=True,
        text=True,
        check=True,
        cwd=top,
    )
    return os.path.join(json.loads(meta.stdout)["target_directory"], profile, "legacy-rt")


if __name__ == "__main__":
    print(built(sys.argv[1] if len(sys.argv) > 1 else "release"))
