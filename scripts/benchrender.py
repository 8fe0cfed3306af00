"""What the render benchmarks (scripts/bench-pictures.py, scripts/bench-paths.py, scripts/bench-render.py) share: their command
line (--runs, --size) and the check that build/gpurt is there. Standard library only."""

import argparse
import os
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
GPURT = os.path.join(ROOT, "build", "gpurt")


def parse_args(doc, name, models=False, size="512x512"):
    """The benchmark's options, or None (after one line on stderr) when build/gpurt is missing;
    `models`: it also takes model files."""
    parser = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--size", default=size)
    if models:
        parser.add_argument("models", nargs="*")
    args = parser.parse_args()
    if not os.path.exists(GPURT):
        print("%s: build/gpurt is missing (run ./run.sh)" % name, file=sys.stderr)
        return None
    return args
