#!/usr/bin/env python3
"""Repeated code that involves GLSL (the `duplicates` tool reads C++ only): runs of at least
--lines consecutive statement lines that appear in two places, at least one of them a kernel file
(glsl/**/*.frag, .glsl, .vert, .h), the other a kernel file or C++ (src/, tools/). A line is
compared with its comments, whitespace and a trailing `f` of float literals stripped, and
declarations' `const ` dropped, so that a GLSL copy of C++ code is found too; lines that are
only punctuation, preprocessor lines and trivial statements (`return;`, `break;`) neither count
nor break a run.

  scripts/glsl-duplicates.py [--lines N]

Prints each repeat (both places and the first line) and exits 1 when there is one that
scripts/glsl-duplicates.allow does not list (a line `FILE:FILE  reason`, the pair in either
order: a repeat kept on purpose, with why). Standard library only."""

import argparse
import os
import re
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
ALLOW = os.path.join(ROOT, "scripts", "glsl-duplicates.allow")
GLSL_EXT = (".frag", ".glsl", ".vert", ".h")
CPP_EXT = (".cpp", ".h")
TRIVIAL = {"return;", "break;", "continue;", "else", "} else {", "#endif", "#else"}


def files():
    for top, exts, kernel in (("glsl", GLSL_EXT, True), ("src", CPP_EXT, False), ("tools", CPP_EXT, False)):
        for folder, _, names in os.walk(os.path.join(ROOT, top)):
            for name in sorted(names):
                if name.endswith(exts):
                    path = os.path.join(folder, name)
                    yield os.path.relpath(path, ROOT), kernel


def statements(path):
    """(line number, normalised text) of the lines that count."""
    out = []
    in_block = False
    with open(os.path.join(ROOT, path), encoding="utf-8", errors="replace") as f:
        for number, line in enumerate(f, 1):
            text = line
            if in_block:
                end = text.find("*/")
                if end < 0:
                    continue
                text = text[end + 2:]
                in_block = False
            text = re.sub(r"/\*.*?\*/", "", text)
            start = text.find("/*")
            if start >= 0:
                text, in_block = text[:start], True
            text = text.split("//", 1)[0].strip()
            if not text or text.startswith("#") or text in TRIVIAL or not re.search(r"[A-Za-z0-9]", text):
                continue
            text = re.sub(r"\s+", " ", text)
            text = re.sub(r"(\d\.\d*(?:e[-+]?\d+)?)f\b", r"\1", text)
            text = re.sub(r"\bconst ", "", text)
            out.append((number, text))
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--lines", type=int, default=6, help="the shortest run reported (default 6)")
    args = parser.parse_args()
    n = args.lines
    texts, kinds = {}, {}
    windows = {}
    for path, kernel in files():
        kinds[path] = kernel
        texts[path] = statements(path)
        lines = texts[path]
        for i in range(len(lines) - n + 1):
            key = tuple(t for _, t in lines[i:i + n])
            windows.setdefault(key, []).append((path, i))
    # Pairs of places, grown to their longest common runs.
    pairs = {}
    for places in windows.values():
        if len(places) < 2:
            continue
        for a in range(len(places)):
            for b in range(a + 1, len(places)):
                (pa, ia), (pb, ib) = places[a], places[b]
                if not (kinds[pa] or kinds[pb]):
                    continue  # C++ with C++: the duplicates tool's
                if pa == pb and abs(ia - ib) < n:
                    continue
                pairs.setdefault((pa, pb), set()).add((ia, ib))
    allowed = set()
    if os.path.exists(ALLOW):
        with open(ALLOW, encoding="utf-8") as f:
            for line in f:
                line = line.split("#", 1)[0].strip()
                if line:
                    a, b = line.split()[0].split(":")[:2]
                    allowed.add((a, b))
                    allowed.add((b, a))
    found = 0
    unexplained = 0
    for (pa, pb), starts in sorted(pairs.items()):
        covered = set()
        for ia, ib in sorted(starts):
            if (ia, ib) in covered:
                continue
            length = 0
            while (ia + length, ib + length) in starts or length < n:
                covered.add((ia + length, ib + length))
                length += 1
                if (ia + length, ib + length) not in starts and length >= n:
                    break
            run = length + n - 1
            la, lb = texts[pa][ia][0], texts[pb][ib][0]
            found += 1
            ok = (pa, pb) in allowed
            unexplained += not ok
            print(f"{'allowed ' if ok else ''}{pa}:{la} and {pb}:{lb}: {run} lines, from `{texts[pa][ia][1]}`")
    print(f"{found} repeats of {n} or more lines involving GLSL, {unexplained} not in scripts/glsl-duplicates.allow")
    return 1 if unexplained else 0


if __name__ == "__main__":
    sys.exit(main())
