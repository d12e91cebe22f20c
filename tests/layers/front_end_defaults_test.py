#!/usr/bin/env python3
"""Defaults and name tables live in the host layer, not in the front ends.

The graspkit program (apps/), Lua (scripting/src), Python (bindings/python/src), the C ABI
(bindings/c/src) and the Rust crate (bindings/rust/graspkit/src) take every default a request
has (the planner, its mode, energy, spaces and budget; the wrench space; body kinds) from the
engine: graspkit/host/ and the enums' name tables (base/enum_names.hpp). This test reads their
code (comments and help text left out) and fails on a default or a name written there again:
the numbers and names below, as code, not prose.

Usage: front_end_defaults_test.py SOURCE_DIR
"""

import re
import sys
from pathlib import Path

FRONT_ENDS = ["apps", "scripting/src", "bindings/c/src", "bindings/python/src",
              "bindings/rust/graspkit/src"]
# What the host layer and the enum tables own: a quoted name as a whole string literal, or the
# default budget as a number.
NAMES = ["restarts", "anneal", "axis-angle", "complete", "ellipsoid", "eigen", "simann",
         "contact", "potential-quality", "L1", "Linf", "LInfinity", "graspable", "obstacle"]
QUOTED = re.compile(r'"(' + "|".join(re.escape(n) for n in NAMES) + r')"')
NUMBER = re.compile(r"\b40000\b")
STRING = re.compile(r'"(?:[^"\\\n]|\\.)*"')


def code_lines(text):
    """(line number, code) with comments removed; string literals kept (checked apart)."""
    text = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.S)
    for number, line in enumerate(text.splitlines(), 1):
        # A // comment (not inside a string: good enough for these sources, checked below).
        stripped = STRING.sub(lambda m: "_" * len(m.group(0)), line)
        cut = stripped.find("//")
        yield number, line if cut < 0 else line[:cut]


def main():
    source = Path(sys.argv[1])
    problems = []
    files = 0
    for folder in FRONT_ENDS:
        for path in sorted((source / folder).rglob("*")):
            if path.suffix not in (".cpp", ".hpp", ".c", ".h", ".rs"):
                continue
            files += 1
            for number, code in code_lines(path.read_text()):
                where = f"{path.relative_to(source)}:{number}"
                # require(pointer, "name") names a C argument, not a setting.
                names = QUOTED.finditer(re.sub(r'require\([^,]+, "[^"]*"\)', "", code))
                for match in names:
                    problems.append(f"{where}: the name \"{match.group(1)}\" (use the host "
                                    f"layer's default or the enum's table)")
                without_strings = STRING.sub("", code)
                if NUMBER.search(without_strings):
                    problems.append(f"{where}: 40000 (host::kDefaultPlanSteps)")
    if files < 50:
        problems.append(f"only {files} front-end files found under {source}")
    if problems:
        print("\n".join(problems))
        return 1
    print(f"{files} front-end files write no default or name the host layer owns")
    return 0


if __name__ == "__main__":
    sys.exit(main())
