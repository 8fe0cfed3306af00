#!/usr/bin/env python3
"""Lists the functions of src/ and tools/ (C++) and glsl/ longer than a limit (default 80 lines).

    scripts/long-functions.py [LIMIT]

A function is a definition whose header line ends in '{' (after its parameters) and whose body ends
at the matching brace; lambdas count in the function that holds them. Prints 'lines file:line name'
for each, longest first; exits 0 (a report, not a check)."""
import os
import re
import sys

LIMIT = int(sys.argv[1]) if len(sys.argv) > 1 else 80
HEADER = re.compile(r'^(\s*)(?!if\b|for\b|while\b|switch\b|else\b|do\b|return\b|namespace\b|struct\b|class\b|enum\b|union\b)'
                    r'[\w:<>,\s\*&~\[\]]*?\b([\w:~]+)\s*\([^;]*\)\s*(const\s*)?(override\s*)?(noexcept\s*)?(->\s*[\w:<>]+\s*)?(:\s*.*)?\{\s*$')


def strip(line):
    line = re.sub(r'"(\\.|[^"\\])*"', '""', line)
    line = re.sub(r"'(\\.|[^'\\])*'", "''", line)
    return line.split('//')[0]


def functions(path):
    lines = open(path, encoding='utf-8', errors='replace').read().split('\n')
    out = []
    i = 0
    while i < len(lines):
        text = strip(lines[i])
        m = HEADER.match(text)
        # a header may span lines: join up to 4 lines ending at one with '{'
        if not m and '(' in text and not text.rstrip().endswith(';'):
            joined = text
            for k in range(1, 5):
                if i + k >= len(lines):
                    break
                joined += ' ' + strip(lines[i + k]).strip()
                if joined.rstrip().endswith('{') or joined.rstrip().endswith(';'):
                    break
            m2 = HEADER.match(joined)
            if m2 and joined.rstrip().endswith('{'):
                m = m2
                i_end_header = i + k
            else:
                i_end_header = i
        else:
            i_end_header = i
        if m and m.group(2) not in ('if', 'for', 'while', 'switch', 'catch'):
            depth = 0
            j = i
            while j < len(lines):
                s = strip(lines[j])
                depth += s.count('{') - s.count('}')
                if depth <= 0 and j >= i_end_header:
                    break
                j += 1
            n = j - i + 1
            if n > LIMIT:
                out.append((n, path, i + 1, m.group(2)))
            i = j + 1
            continue
        i += 1
    return out


def main():
    found = []
    for root in ('src', 'tools', 'glsl'):
        for dirpath, _, files in os.walk(root):
            for f in files:
                if f.endswith(('.cpp', '.h', '.frag', '.glsl', '.vert')):
                    found += functions(os.path.join(dirpath, f))
    for n, path, line, name in sorted(found, reverse=True):
        print(f'{n:5d} {path}:{line} {name}')


if __name__ == '__main__':
    main()
