#!/usr/bin/env python3
"""The doc test: every graspkit command the README and the docs show is run, so they cannot drift.

Usage: doc_commands.py SOURCE_DIR BUILD_DIR GRASPKIT WORK_DIR [SHARED_DIR]

What counts as a command:
  - a line of a ```sh / ```bash block, or of an indented block, that starts with `graspkit` or
    `./build/apps/graspkit/graspkit`;
  - an inline `graspkit ...` code span in a table row (examples/README.md).
A command with placeholders (FILE, [--robot N], ...) is a synopsis: each option it names must be
in that subcommand's --help. Any other command is run from a scratch copy of the checkout
(models/, examples/, docs/ and build/ linked in, ../shared beside it) and must exit 0. A ```lua
block after `<!-- doc-test: save as NAME -->` is written to NAME first, so that a script the
docs show can be run as they say. Lines that run something else (scripts/dev, cmake, cargo, an
install's program) are counted and named with the test that runs them.
"""

import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

DOC_FILES = [
    "README.md",
    "docs/*.md",
    "examples/README.md",
    "examples/*/README.md",
    "bindings/rust/README.md",
    "plugins/planners/README.md",
    "scripting/README.md",
    "models/README.md",
]
PROGRAM_PREFIXES = ("graspkit ", "./build/apps/graspkit/graspkit ")
# What runs the other commands the docs show.
COVERED_ELSEWHERE = [
    (re.compile(r"^scripts/dev\b"), ".ci/run (scripts/dev test, scripts/dev asan)"),
    (re.compile(r"^cmake\b"), "package.custom_robot_plugin, package.embedding"),
    (re.compile(r"^(cd bindings/rust|RUSTC=\S+ /usr/bin/cargo)\b"), "rust.crate"),
    (re.compile(r"^(export GRASPKIT_PLUGIN_PATH|\$HOME/graspkit/bin/graspkit|build-example/)"),
     "package.custom_robot_plugin"),
    (re.compile(r"^(cc|c\+\+|g\+\+|pkg-config)\b"), "package.embedding"),
    (re.compile(r"^PREFIX/bin/graspkit\b"), "package.installed_program"),
    (re.compile(r"^PYTHONPATH=build/bindings/python /usr/bin/python3 examples/python/"),
     "python.module (tests/python/test_examples.py)"),
]
PLACEHOLDER = re.compile(r"\[|\.\.\.|\b(?:[A-Z][A-Z0-9_]*(?:\.lua)?)\b(?![=/])")


def doc_files(source):
    files = []
    for pattern in DOC_FILES:
        files.extend(sorted(source.glob(pattern)))
    return files


def strip_comment(line):
    # A `#` after whitespace starts a shell comment (not inside --set key=#...: none in the docs).
    return re.sub(r"\s+#\s.*$", "", line).rstrip()


def joined_lines(lines):
    """Lines with trailing backslashes joined, as the shell reads them; an indented line goes on
    the synopsis above it."""
    out, pending = [], ""
    for line in lines:
        if line.rstrip().endswith("\\"):
            pending += line.rstrip()[:-1] + " "
            continue
        if line.startswith((" ", "\t")) and out and not pending:
            out[-1] += " " + line.strip()
            continue
        out.append((pending + line).strip())
        pending = ""
    if pending:
        out.append(pending.strip())
    return out


def extract(path):
    """Yields (line_number, kind, text): kind is 'shell' for commands, 'save:NAME' for scripts."""
    lines = path.read_text().splitlines()
    i, save_as = 0, None
    while i < len(lines):
        line = lines[i]
        fence = re.match(r"^\s*```(\w*)\s*$", line)
        marker = re.match(r"^\s*<!--\s*doc-test:\s*save as\s+(\S+)\s*-->", line)
        if marker:
            save_as = marker.group(1)
        elif fence:
            language, start, body = fence.group(1), i + 1, []
            i += 1
            while i < len(lines) and not re.match(r"^\s*```\s*$", lines[i]):
                body.append(lines[i])
                i += 1
            if language in ("sh", "bash", "shell"):
                for text in joined_lines(body):
                    yield start + 1, "shell", strip_comment(text)
            elif language == "lua" and save_as:
                yield start, "save:" + save_as, "\n".join(body) + "\n"
                save_as = None
        elif line.startswith("    ") and line.strip().startswith(PROGRAM_PREFIXES):
            yield i + 1, "shell", strip_comment(line.strip())
        elif line.lstrip().startswith("|"):
            # A table cell holding a whole command: `graspkit SUBCOMMAND ARGUMENT ...`, possibly
            # after `mkdir -p DIR &&` (not `graspkit plan`'s or `graspkit plan --preset`).
            for span in re.findall(r"`((?:mkdir -p \S+ && )?graspkit [^`]+)`", line):
                words = span.split("&&")[-1].split()
                if len(words) >= 3 and not words[2].startswith("-"):
                    yield i + 1, "shell", span
        i += 1


def subcommand_help(graspkit, words):
    sub = next((w for w in words[1:] if not w.startswith("-")), None)
    command = [graspkit] + ([sub] if sub else []) + ["--help"]
    return subprocess.run(command, capture_output=True, text=True, timeout=60).stdout


def check_synopsis(graspkit, text):
    words = text.split()
    help_text = subcommand_help(graspkit, words)
    missing = [o for o in re.findall(r"(?<![\w-])(--?[a-zA-Z][\w-]*)", text)
               if not re.search(r"(?<![\w-])" + re.escape(o) + r"\b", help_text)]
    return f"options not in --help: {', '.join(missing)}" if missing else None


def runnable(text):
    # An optional tail in brackets ("[-- WORLD]") is left off; placeholders elsewhere make a
    # synopsis.
    text = re.sub(r"(\s+\[[^\]]*\])+$", "", text)
    return None if PLACEHOLDER.search(text.split(" ", 1)[1] if " " in text else "") else text


def scratch_checkout(source, build, shared, work):
    root = work / "checkout"
    if work.exists():
        shutil.rmtree(work)
    root.mkdir(parents=True)
    for name in ("models", "examples", "docs", "bindings", "plugins", "scripting"):
        (root / name).symlink_to(source / name)
    (root / "build").symlink_to(build)
    if shared:
        (work / "shared").symlink_to(shared)
    return root


def run_command(graspkit, root, text):
    # `mkdir -p DIR && ` before a command: the folder is made here, not by a shell.
    while (made := re.match(r"^mkdir -p (\S+) && (.*)$", text)):
        (root / made.group(1)).mkdir(parents=True, exist_ok=True)
        text = made.group(2)
    words = shlex.split(text)
    words[0] = graspkit
    env = dict(os.environ, HOME=str(root))
    result = subprocess.run(words, cwd=root, env=env, capture_output=True, text=True,
                            timeout=600)
    if result.returncode != 0:
        return f"exit {result.returncode}\n{result.stderr[-2000:]}"
    return None


def main():
    source, build, graspkit, work = (Path(a).resolve() for a in sys.argv[1:5])
    shared = Path(sys.argv[5]).resolve() if len(sys.argv) > 5 and sys.argv[5] else None
    if shared and not shared.is_dir():
        shared = None
    root = scratch_checkout(source, build, shared, work)
    failures, counts, elsewhere = [], {"run": 0, "synopsis": 0, "saved": 0}, {}
    for path in doc_files(source):
        where = path.relative_to(source)
        for line, kind, text in extract(path):
            if kind.startswith("save:"):
                (root / kind[5:]).write_text(text)
                counts["saved"] += 1
                continue
            if not text or text.startswith(("graspkit:", "$ ")):
                continue
            program = re.sub(r"^mkdir -p \S+ && ", "", text)
            if not program.startswith(PROGRAM_PREFIXES) and text != "graspkit":
                cover = next((c for p, c in COVERED_ELSEWHERE if p.search(text)), None)
                if cover is None:
                    failures.append(f"{where}:{line}: a command no test runs: {text}")
                else:
                    elsewhere.setdefault(cover, []).append(f"{where}:{line}")
                continue
            command = runnable(text) if program == text else text
            if command != text:  # a synopsis, or a command with an optional tail
                counts["synopsis"] += 1
                if problem := check_synopsis(graspkit, program):
                    failures.append(f"{where}:{line}: {text}\n  {problem}")
            if command is None:
                continue
            if "../shared" in command and shared is None:
                print(f"SKIPPED {where}:{line}: needs ../shared: {command}", flush=True)
                continue
            counts["run"] += 1
            print(f"run {where}:{line}: {command}", flush=True)
            if problem := run_command(str(graspkit), root, command):
                failures.append(f"{where}:{line}: {command}\n  {problem}")
    print(f"{counts['run']} commands run, {counts['synopsis']} synopses checked against --help, "
          f"{counts['saved']} scripts saved from the docs")
    for cover, places in sorted(elsewhere.items()):
        print(f"run by {cover}: {len(places)} lines ({', '.join(places)})")
    for failure in failures:
        print("FAILED " + failure)
    return 1 if failures or counts["run"] == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
