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
install's program) are counted and named with the test that runs them. A line that starts with
`mpirun` runs the graspkit command after mpirun's own options under mpirun, as shown (skipped when
mpirun is not installed): as root, Open MPI refuses to start without --allow-run-as-root, so a doc
that leaves it out fails here.

Figures the docs quote from a command's output are checked against what the command prints:
  - `<!-- doc-test: output -->` before a fenced block (no language, or `text`) says the block is
    the stdout of the command just above it (the last command of the block before): line by line
    the same words; a line `...` stands for any lines, `...` within a line for any text;
  - `<!-- doc-test: figures "PHRASE" ... from COMMAND -->` before a paragraph says each PHRASE
    (words and one or more numbers, e.g. "volume 0.003921828") is in the paragraph and in what
    COMMAND prints (COMMAND is run as a doc command is).
A number is compared to the digits the doc shows: it matches when it rounds to them (0.0039218
matches 0.003921828, 0.0039213 does not). A number followed by the unit `s` or `ms` is a timing and
is not compared.
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
# `graspkit serve` runs until it is stopped: its lines are checked against --help and left to the
# tests that start and drive a server.
SERVE = re.compile(r"^(?:\./build/apps/graspkit/)?graspkit (?:-q )?serve\b")
SERVE_TESTS = "editor.page, cli.serve_requests"
NUMBER = r"-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?"
# A number standing alone (not `chain0`, `d0+25` or a version 1.0.0), and whether a unit of time
# follows it.
NUMBER_TOKEN = re.compile(r"(?<![\w.])(" + NUMBER + r")(?![\w]|\.\d)(\s?m?s\b)?")
MPIRUN_VALUE_OPTIONS = {"-np", "-n", "-c", "--np", "--host", "-H", "--map-by", "--bind-to",
                        "--hostfile", "--mca", "-x"}
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
        output = re.match(r"^\s*<!--\s*doc-test:\s*output\s*-->", line)
        figures = re.match(r"^\s*<!--\s*doc-test:\s*figures\s+(.*?)\s+from\s+(.+?)\s*-->", line)
        if marker:
            save_as = marker.group(1)
        elif output:
            i += 1
            while i < len(lines) and not lines[i].strip():
                i += 1
            fence = re.match(r"^\s*```(\w*)\s*$", lines[i]) if i < len(lines) else None
            if not fence or fence.group(1) not in ("", "text"):
                yield i + 1, "error", "<!-- doc-test: output --> is not followed by an output block"
                continue
            start, body = i + 1, []
            i += 1
            while i < len(lines) and not re.match(r"^\s*```\s*$", lines[i]):
                body.append(lines[i])
                i += 1
            yield start, "output", "\n".join(body)
        elif figures:
            paragraph, j = [], i + 1
            while j < len(lines) and lines[j].strip():
                paragraph.append(lines[j].strip())
                j += 1
            phrases = re.findall(r'"([^"]+)"', figures.group(1))
            yield i + 1, "figures", (phrases, figures.group(2), " ".join(paragraph))
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


def digits_match(shown, printed):
    """Whether `printed` rounds to the figure `shown` (to the digits shown)."""
    mantissa, _, exponent = shown.lower().partition("e")
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    unit = 10.0 ** (int(exponent or 0) - decimals)
    return abs(float(printed) - float(shown)) <= 0.5 * unit * (1 + 1e-9)


def pattern_of(text):
    """A regex for one line or phrase of a doc: numbers captured, `...` any text, spaces any run."""
    parts, figures, at = [], [], 0
    for m in NUMBER_TOKEN.finditer(text):
        parts.append(literal_pattern(text[at:m.start()]))
        parts.append("(" + NUMBER + ")" + (r"\s?m?s\b" if m.group(2) else ""))
        figures.append(None if m.group(2) else m.group(1))  # a timing: not compared
        at = m.end()
    parts.append(literal_pattern(text[at:]))
    return "".join(parts), figures


def literal_pattern(text):
    pieces = [re.escape(p) for p in text.split("...")]
    return ".*?".join(re.sub(r"(\\\s)+", r"\\s+", p) for p in pieces)


def compare_figures(pattern, figures, found, where):
    """Problems with the numbers `found` (a regex match) against the doc's `figures`."""
    problems = []
    for shown, printed in zip(figures, found.groups()):
        if shown is not None and not digits_match(shown, printed):
            problems.append(f"{where}: the doc shows {shown}, the command prints {printed}")
    return problems


def check_output_block(expected, printed):
    """Problems of a doc's output block against the command's stdout (None when it matches)."""
    patterns, figures = [], []
    for line in expected.splitlines():
        if line.strip() == "...":
            patterns.append(r"(?:[^\n]*\n)*?")
            continue
        pattern, numbers = pattern_of(line.strip())
        patterns.append(r"[ \t]*" + pattern + r"[ \t]*\n")
        figures.extend(numbers)
    found = re.fullmatch("".join(patterns), printed.rstrip("\n") + "\n")
    if not found:
        return [f"the output block is not what the command prints; it prints:\n{printed}"]
    return compare_figures(patterns, figures, found, "output") or None


def check_figures(phrases, paragraph, printed):
    problems = []
    flat = re.sub(r"[`*]", "", paragraph)
    for phrase in phrases:
        if phrase not in flat:
            problems.append(f'"{phrase}" is not in the paragraph below the comment')
        pattern, figures = pattern_of(phrase)
        found = re.search(r"(?<![\w.-])" + pattern, printed)
        if not found:
            problems.append(f'"{phrase}": nothing like it in what the command prints:\n{printed}')
            continue
        problems.extend(compare_figures(pattern, figures, found, f'"{phrase}"'))
    return problems or None


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


def mpirun_split(text):
    """(mpirun and its options, the program's command) of an `mpirun ...` line."""
    words = shlex.split(text)
    i = 1
    while i < len(words) and words[i].startswith("-"):
        i += 2 if words[i] in MPIRUN_VALUE_OPTIONS else 1
    return words[:i], " ".join(shlex.quote(w) for w in words[i:])


def run_command(graspkit, root, text):
    """(problem or None, stdout)."""
    # `mkdir -p DIR && ` before a command: the folder is made here, not by a shell.
    while (made := re.match(r"^mkdir -p (\S+) && (.*)$", text)):
        (root / made.group(1)).mkdir(parents=True, exist_ok=True)
        text = made.group(2)
    launcher = []
    if text.startswith("mpirun "):
        launcher, text = mpirun_split(text)
        launcher[0] = shutil.which("mpirun")
    words = shlex.split(text)
    words[0] = graspkit
    env = dict(os.environ, HOME=str(root))
    for variable in ("OMPI_ALLOW_RUN_AS_ROOT", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"):
        env.pop(variable, None)  # the doc's own line must be enough
    result = subprocess.run(launcher + words, cwd=root, env=env, capture_output=True, text=True,
                            timeout=600)
    if result.returncode != 0:
        return f"exit {result.returncode}\n{result.stderr[-2000:]}", result.stdout
    return None, result.stdout


def main():
    source, build, graspkit, work = (Path(a).resolve() for a in sys.argv[1:5])
    shared = Path(sys.argv[5]).resolve() if len(sys.argv) > 5 and sys.argv[5] else None
    if shared and not shared.is_dir():
        shared = None
    root = scratch_checkout(source, build, shared, work)
    failures, elsewhere = [], {}
    counts = {"run": 0, "synopsis": 0, "saved": 0, "outputs": 0, "figures": 0}
    for path in doc_files(source):
        where = path.relative_to(source)
        # (line, command, stdout) of the last command in this file: stdout None when it was
        # skipped here, False when this test does not run it (a synopsis, another test's)
        last = None
        for line, kind, text in extract(path):
            if kind.startswith("save:"):
                (root / kind[5:]).write_text(text)
                counts["saved"] += 1
                continue
            if kind == "error":
                failures.append(f"{where}:{line}: {text}")
                continue
            if kind == "output":
                if last is None or last[2] is False:
                    failures.append(f"{where}:{line}: an output block with no command run above it")
                elif last[2] is None:
                    print(f"SKIPPED {where}:{line}: the output of {last[1]} (not run)", flush=True)
                else:
                    counts["outputs"] += 1
                    if problems := check_output_block(text, last[2]):
                        failures.append(f"{where}:{line}: output of {last[1]}\n  " +
                                        "\n  ".join(problems))
                continue
            if kind == "figures":
                phrases, command, paragraph = text
                if not phrases or not command.startswith(PROGRAM_PREFIXES):
                    failures.append(f"{where}:{line}: a figures comment needs \"PHRASE\"s and a "
                                    f"graspkit command: {command}")
                    continue
                if "../shared" in command and shared is None:
                    print(f"SKIPPED {where}:{line}: needs ../shared: {command}", flush=True)
                    continue
                counts["figures"] += len(phrases)
                problem, printed = run_command(str(graspkit), root, command)
                problems = [problem] if problem else check_figures(phrases, paragraph, printed)
                if problems:
                    failures.append(f"{where}:{line}: figures from {command}\n  " +
                                    "\n  ".join(problems))
                continue
            if not text or text.startswith(("graspkit:", "$ ")):
                continue
            if text.startswith("mpirun "):
                launcher, program = mpirun_split(text)
                if not program.startswith(PROGRAM_PREFIXES):
                    failures.append(f"{where}:{line}: mpirun runs something else: {text}")
                    continue
                if runnable(program) != program:
                    counts["synopsis"] += 1
                    last = (line, text, False)
                    if problem := check_synopsis(graspkit, program):
                        failures.append(f"{where}:{line}: {text}\n  {problem}")
                    continue
                if not shutil.which("mpirun"):
                    print(f"SKIPPED {where}:{line}: mpirun is not installed: {text}", flush=True)
                    last = (line, text, None)
                    continue
                counts["run"] += 1
                print(f"run {where}:{line}: {text}", flush=True)
                problem, printed = run_command(str(graspkit), root, text)
                last = (line, text, printed)
                if problem:
                    failures.append(f"{where}:{line}: {text}\n  {problem}")
                continue
            program = re.sub(r"^mkdir -p \S+ && ", "", text)
            if not program.startswith(PROGRAM_PREFIXES) and text != "graspkit":
                cover = next((c for p, c in COVERED_ELSEWHERE if p.search(text)), None)
                if cover is None:
                    failures.append(f"{where}:{line}: a command no test runs: {text}")
                else:
                    elsewhere.setdefault(cover, []).append(f"{where}:{line}")
                last = (line, text, False)
                continue
            command = runnable(text) if program == text else text
            if command != text:  # a synopsis, or a command with an optional tail
                counts["synopsis"] += 1
                if problem := check_synopsis(graspkit, program):
                    failures.append(f"{where}:{line}: {text}\n  {problem}")
            if command is None:
                last = (line, text, False)
                continue
            if SERVE.match(command):
                if command == text and (problem := check_synopsis(graspkit, program)):
                    failures.append(f"{where}:{line}: {text}\n  {problem}")
                elsewhere.setdefault(SERVE_TESTS, []).append(f"{where}:{line}")
                last = (line, text, False)
                continue
            if "../shared" in command and shared is None:
                print(f"SKIPPED {where}:{line}: needs ../shared: {command}", flush=True)
                last = (line, command, None)
                continue
            counts["run"] += 1
            print(f"run {where}:{line}: {command}", flush=True)
            problem, printed = run_command(str(graspkit), root, command)
            last = (line, command, printed)
            if problem:
                failures.append(f"{where}:{line}: {command}\n  {problem}")
    print(f"{counts['run']} commands run, {counts['synopsis']} synopses checked against --help, "
          f"{counts['saved']} scripts saved from the docs, {counts['outputs']} output blocks and "
          f"{counts['figures']} quoted figures compared with what the commands print")
    for cover, places in sorted(elsewhere.items()):
        print(f"run by {cover}: {len(places)} lines ({', '.join(places)})")
    for failure in failures:
        print("FAILED " + failure)
    return 1 if failures or counts["run"] == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
