#!/usr/bin/env python3
"""Runs the gpurt command lines of the documents, so that what they show keeps working.

    scripts/check-docs.py GPURT [DOCUMENT...]      (default: README.md docs/USAGE.md)

Takes every line of a fenced code block that starts with `gpurt `, `./build/gpurt ` or
`build/gpurt ` (a trailing backslash continues it) and runs it with the binary GPURT from the
repository root, without a shell, made small so that the check is quick: --size at most 32x24
(added where render and bench lack it), --spp and --min-spp at most 4, --frames A:B at most two
frames, --time-limit at most 1 s, bench's --runs at most 1. Values that are not well formed are
left as written (a refusal example may need them). Output files (-o, --aov KIND=FILE,
--screenshot, --dump) go to a temporary folder, one per document; an input file that is not in
the repository is looked for there, so a document's later lines read what its earlier ones wrote.

Skipped: `gpurt view` (it needs a window) and lines whose trailing comment starts with `not run`.
A line whose trailing comment starts with `exit N` must exit with status N; every other line must
exit 0. Prints how many lines ran; exits 1, naming the document, line, command and its stderr,
when any fails.
"""
import glob
import os
import re
import shlex
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DOCUMENTS = ["README.md", "docs/USAGE.md"]
PREFIXES = ("gpurt ", "./build/gpurt ", "build/gpurt ")

MAX_SIZE = (32, 24)
MAX_SPP = 4
MAX_FRAMES = 2
MAX_TIME_LIMIT = 1.0
MAX_RUNS = 1
TIMEOUT_S = 120

# Options that take no value (every other option takes one, as `--opt VALUE` or `--opt=VALUE`).
FLAGS = {"-h", "--help", "--progress", "--quiet", "--denoise", "--mask-paths", "--json", "--bench",
         "--no-denoise", "--stats"}
OUTPUTS = {"-o", "--output", "--screenshot", "--dump"}
INPUTS = {"--albedo", "--normal", "--depth", "--variance", "--env", "--glsl-dir"}
SIZED = {"render", "bench", "view"}
SHELL = {"|", "||", "&&", ";", "&", ">", ">>", "<", "2>", "2>&1"}


def code_lines(path):
    """(line number, text) of each logical line inside the fenced code blocks of a document."""
    lines = []
    fenced = False
    pending, first = "", 0
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            line = line.rstrip("\n")
            if not pending and line.lstrip().startswith("```"):
                fenced = not fenced
                continue
            if not fenced:
                continue
            if not pending:
                first = number
            if line.endswith("\\"):
                pending += line[:-1] + " "
                continue
            lines.append((first, pending + line))
            pending = ""
    return lines


def split_comment(line):
    """The command and its trailing comment: from the first # outside quotes after a blank."""
    quote = None
    for i, c in enumerate(line):
        if quote:
            if c == quote:
                quote = None
        elif c in "'\"":
            quote = c
        elif c == "#" and (i == 0 or line[i - 1].isspace()):
            return line[:i].strip(), line[i + 1:].strip()
    return line.strip(), ""


def smaller_size(value):
    m = re.fullmatch(r"(\d+)x(\d+)", value)
    if not m:
        return value
    w, h = int(m.group(1)), int(m.group(2))
    return "%dx%d" % (min(w, MAX_SIZE[0]), min(h, MAX_SIZE[1]))


def capped_int(value, most):
    return str(min(int(value), most)) if re.fullmatch(r"\d+", value) else value


def capped_frames(value):
    m = re.fullmatch(r"(\d+):(\d+)", value)
    if not m:
        return value
    a, b = int(m.group(1)), int(m.group(2))
    return "%d:%d" % (a, min(b, a + MAX_FRAMES - 1))


def capped_seconds(value):
    try:
        seconds = float(value)
    except ValueError:
        return value
    return value if not seconds > MAX_TIME_LIMIT else "%g" % MAX_TIME_LIMIT


class Rewriter:
    """Turns a documented command line into a quick one whose files live in `work`."""

    def __init__(self, work):
        self.work = work

    def output(self, path):
        parts = [p if p != ".." else "__" for p in path.split("/") if p not in ("", ".")]
        full = os.path.join(self.work, *parts)
        os.makedirs(os.path.dirname(full), exist_ok=True)
        return full

    def inputs(self, path):
        if any(c in path for c in "*?["):
            found = sorted(glob.glob(os.path.join(self.work, path))) or sorted(glob.glob(path))
            return found or [path]
        if os.path.exists(path) or not os.path.exists(os.path.join(self.work, path)):
            return [path]
        return [os.path.join(self.work, path)]

    def value(self, command, option, value):
        if option in OUTPUTS:
            return self.output(value)
        if option == "--aov" and "=" in value:
            kind, path = value.split("=", 1)
            return kind + "=" + self.output(path)
        if option in INPUTS:
            return self.inputs(value)[0]
        if option == "--size":
            return smaller_size(value)
        if option in ("--spp", "--min-spp"):
            return capped_int(value, MAX_SPP)
        if option == "--frames":
            return capped_frames(value) if command == "render" else capped_int(value, MAX_FRAMES)
        if option == "--time-limit":
            return capped_seconds(value)
        if option == "--runs":
            return capped_int(value, MAX_RUNS)
        return value

    def rewrite(self, gpurt, words):
        command = words[0] if words else ""
        out = [gpurt, command]
        sized = False
        i = 1
        while i < len(words):
            word = words[i]
            i += 1
            if word.startswith("-") and len(word) > 1:
                option, given, value = word.partition("=")
                if not given and option not in FLAGS and i < len(words):
                    value, i = words[i], i + 1
                    given = True
                sized = sized or option == "--size"
                if given:
                    value = self.value(command, option, value)
                    out += [option + "=" + value] if "=" in word else [option, value]
                else:
                    out.append(word)
            else:
                out += self.inputs(word)
        if command in SIZED and not sized and "--help" not in words and "-h" not in words:
            out += ["--size", "%dx%d" % MAX_SIZE]
        return out


def check(gpurt, document):
    """Runs a document's command lines; returns (ran, skipped, failures)."""
    ran, skipped, failures = 0, 0, []
    with tempfile.TemporaryDirectory(prefix="gpurt-docs-") as work:
        rewriter = Rewriter(work)
        for number, line in code_lines(os.path.join(ROOT, document)):
            text = line.strip()
            prefix = next((p for p in PREFIXES if text.startswith(p)), None)
            if prefix is None:
                continue
            command, comment = split_comment(text[len(prefix):])
            where = "%s:%d" % (document, number)
            words = shlex.split(command)
            if (words and words[0] == "view") or comment.startswith("not run"):
                skipped += 1
                continue
            if any(w in SHELL for w in words):
                failures.append("%s: shell syntax; the check runs commands without a shell: %s"
                                % (where, text))
                continue
            m = re.match(r"exit (\d+)\b", comment)
            expected = int(m.group(1)) if m else 0
            argv = rewriter.rewrite(gpurt, words)
            ran += 1
            try:
                run = subprocess.run(argv, cwd=ROOT, stdin=subprocess.DEVNULL, capture_output=True,
                                     text=True, errors="replace", timeout=TIMEOUT_S)
            except subprocess.TimeoutExpired:
                failures.append("%s: did not end within %d s: %s\n  ran: %s"
                                % (where, TIMEOUT_S, text, shlex.join(argv)))
                continue
            if run.returncode != expected:
                failures.append("%s: exit %d, expected %d: %s\n  ran: %s\n  stderr: %s"
                                % (where, run.returncode, expected, text, shlex.join(argv),
                                   run.stderr.strip()[-2000:].replace("\n", "\n          ")))
    return ran, skipped, failures


def main():
    if len(sys.argv) < 2:
        print(__doc__.strip().splitlines()[2].strip(), file=sys.stderr)
        return 2
    gpurt = os.path.abspath(sys.argv[1])
    if not os.access(gpurt, os.X_OK):
        print("check-docs: %s is not an executable" % sys.argv[1], file=sys.stderr)
        return 2
    documents = sys.argv[2:] or DOCUMENTS
    os.chdir(ROOT)  # the documents' paths are the repository's
    start = time.monotonic()
    ran = skipped = 0
    failures = []
    for document in documents:
        r, s, f = check(gpurt, document)
        print("%s: %d command lines ran, %d skipped" % (document, r, s))
        ran, skipped, failures = ran + r, skipped + s, failures + f
    for failure in failures:
        print(failure)
    print("check-docs: %d command lines ran (%d skipped), %d failed, in %.1f s"
          % (ran, skipped, len(failures), time.monotonic() - start))
    if ran == 0:
        print("check-docs: no command line found in %s" % ", ".join(documents))
        return 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
