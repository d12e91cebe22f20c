#!/usr/bin/env python3
"""The excerpt test: code the docs quote from a program that a test runs must be in it.

A fenced block right after `<!-- doc-test: excerpt of PATH -->` (PATH from the project root)
must appear in that file: its lines, stripped of leading and trailing blanks, in order, each
line the same as a line of the file (other lines may come between them). The C and Rust
examples of docs/embedding.md are quoted this way from the programs the parity test runs
(tests/parity), so what the docs show is what runs.

Usage: doc_excerpts.py SOURCE_DIR
"""

import re
import sys
from pathlib import Path

MARKER = re.compile(r"<!-- doc-test: excerpt of (\S+) -->")


def blocks(text):
    """(path, first line number, lines) for each marked block."""
    lines = text.splitlines()
    for i, line in enumerate(lines):
        match = MARKER.search(line)
        if not match:
            continue
        j = i + 1
        while j < len(lines) and not lines[j].startswith("```"):
            j += 1
        k = j + 1
        while k < len(lines) and not lines[k].startswith("```"):
            k += 1
        yield match.group(1), j + 2, lines[j + 1:k]


def contains_in_order(haystack, needles):
    """The first needle not found after the previous ones, or None."""
    position = 0
    for needle in needles:
        while position < len(haystack) and haystack[position] != needle:
            position += 1
        if position == len(haystack):
            return needle
        position += 1
    return None


def main():
    source = Path(sys.argv[1])
    checked, problems = 0, []
    for doc in sorted(source.glob("docs/*.md")) + [source / "README.md"]:
        for path, line, excerpt in blocks(doc.read_text()):
            target = source / path
            if not target.is_file():
                problems.append(f"{doc.name}:{line}: {path} does not exist")
                continue
            program = [l.strip() for l in target.read_text().splitlines()]
            wanted = [l.strip() for l in excerpt if l.strip() and l.strip() != "..."]
            missing = contains_in_order(program, wanted)
            if missing is not None:
                problems.append(f"{doc.name}:{line}: not in {path} (in this order): {missing}")
            checked += 1
    if problems:
        print("\n".join(problems))
        return 1
    if checked == 0:
        print("FAILED: no marked excerpt found")
        return 1
    print(f"{checked} excerpts are in the programs they quote")
    return 0


if __name__ == "__main__":
    sys.exit(main())
