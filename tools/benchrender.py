"""What the render benchmarks (tools/bench-pictures.py, tools/bench-paths.py) share: their command
line (--runs, --size) and the check that build/gpurt is there. Standard library only."""

import argparse
import os
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
GPURT = os.path.join(ROOT, "build", "gpurt")


def parse_args(doc, name):
    """The benchmark's options, or None (after one line on stderr) when build/gpurt is missing."""
    parser = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--size", default="512x512")
    args = parser.parse_args()
    if not os.path.exists(GPURT):
        print("%s: build/gpurt is missing (run ./run.sh)" % name, file=sys.stderr)
        return None
    return args
