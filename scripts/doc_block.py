#!/usr/bin/python3
"""A generated block of a document, between two marker comments: written or checked.

    replace_or_check(path, begin, end, text, check, prog, what, fix) -> exit status

Used by scripts/cost_tables.py (docs/rtl.md's cost tables) and scripts/rtl_builds.py (its build
table): the block is a newline and `text`; --check fails, naming `fix`, when it differs.
"""

import sys
from pathlib import Path


def replace_or_check(path, begin, end, text, check, prog, what, fix):
    doc = Path(path).read_text()
    if doc.count(begin) != 1 or doc.count(end) != 1:
        print(f"{prog}: error: {path} has no single {begin} ... {end} block", file=sys.stderr)
        return 1
    head, rest = doc.split(begin, 1)
    current, tail = rest.split(end, 1)
    block = "\n" + text
    if check:
        if current != block:
            print(f"{prog}: {path}: {what} differs; run {fix}", file=sys.stderr)
            return 1
        print(f"{prog}: {path}: {what} current")
        return 0
    Path(path).write_text(head + begin + block + end + tail)
    return 0
