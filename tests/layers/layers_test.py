#!/usr/bin/env python3
"""The engine's layers, checked three ways against engine/CMakeLists.txt (where they are declared):

1. docs/architecture.md's module table names exactly the declared modules, in the declared order,
   each with the modules it may use; and the module folders (engine/src, engine/include/graspkit)
   are exactly those modules.
2. Every `#include "..."` in engine/ names a header of the including module or of a module it
   may use (directly or through those): read from the files themselves, not from the build.
3. The build's include views refuse a back-include: a scratch file compiled as module `geometry`
   cannot include `graspkit/model/world.hpp` (the compiler says the file does not exist), while
   the same file including a header of `base` compiles.
4. tests/unit/ mirrors the engine: each test file sits in the folder of a module (or of the
   front ends' scripting/ and the planner plugins' plugins/), none at the top.

Usage: layers_test.py SOURCE_DIR BINARY_DIR CXX_COMPILER
"""
import os
import re
import subprocess
import sys
import tempfile

failures = []


def fail(message):
    failures.append(message)
    print("FAIL:", message)


def declared_modules(source):
    """[(module, [uses...])] in declaration order, from engine/CMakeLists.txt."""
    text = open(os.path.join(source, "engine", "CMakeLists.txt"), encoding="utf-8").read()
    modules = []
    for m in re.finditer(r"^graspkit_module\(([\w/]+)((?:\s+USES)?[^)]*)\)", text, re.M):
        uses = m.group(2).split()
        if uses and uses[0] == "USES":
            uses = uses[1:]
        modules.append((m.group(1), uses))
    return modules


def documented_modules(source):
    """[(module, [uses...])] from the table under '| module | may use |' in architecture.md."""
    lines = open(os.path.join(source, "docs", "architecture.md"), encoding="utf-8").read().splitlines()
    rows, inside = [], False
    for line in lines:
        if line.startswith("| module | may use |"):
            inside = True
            continue
        if inside:
            if not line.startswith("|"):
                break
            cells = [c.strip() for c in line.strip("|").split("|")]
            if set(cells[0]) <= set("-"):
                continue
            name = cells[0].strip("`")
            uses = re.findall(r"`([\w/]+)`", cells[1])
            rows.append((name, uses))
    return rows


def module_of(relative):
    parts = relative.split("/")
    return "/".join(parts[:2]) if parts[0] == "io" else parts[0]


def module_folders(root):
    """Module names that hold files under root (io/<format> for io)."""
    found = set()
    for folder, _, files in os.walk(root):
        if any(f.endswith((".hpp", ".cpp")) for f in files):
            found.add(module_of(os.path.relpath(folder, root)))
    return found


def check_tables(source, modules):
    names = [m for m, _ in modules]
    documented = documented_modules(source)
    if not documented:
        fail("docs/architecture.md has no '| module | may use |' table")
    elif documented != modules:
        for (a, ua), (b, ub) in zip(documented, modules):
            if a != b or ua != ub:
                fail(f"docs/architecture.md says {a} may use {ua}; engine/CMakeLists.txt says {b} may use {ub}")
                break
        if len(documented) != len(modules):
            fail(f"docs/architecture.md lists {len(documented)} modules, engine/CMakeLists.txt {len(modules)}")
    for root in ("engine/src", "engine/include/graspkit"):
        folders = module_folders(os.path.join(source, root))
        if folders - set(names):
            fail(f"{root} has folders no module declares: {sorted(folders - set(names))}")
        if root == "engine/src" and set(names) - folders:
            fail(f"{root} lacks folders of declared modules: {sorted(set(names) - folders)}")


def check_unit_tests(source, modules):
    root = os.path.join(source, "tests", "unit")
    allowed = {m for m, _ in modules} | {"scripting", "plugins"}
    for folder, _, files in os.walk(root):
        tests = [f for f in files if f.endswith("_test.cpp")]
        if not tests:
            continue
        where = os.path.relpath(folder, root)
        if where == "." or where not in allowed:
            fail(f"tests/unit/{where}: {tests[0]} is not in a module's folder")


def visible_sets(modules):
    visible = {}
    for name, uses in modules:
        seen = {name}
        for dep in uses:
            seen |= visible.get(dep, {dep})
        visible[name] = seen
    return visible


def check_includes(source, modules):
    visible = visible_sets(modules)
    count, sources = 0, 0
    for base in ("engine/include/graspkit", "engine/src"):
        root = os.path.join(source, base)
        for folder, _, files in os.walk(root):
            for f in files:
                path = os.path.join(folder, f)
                owner = module_of(os.path.relpath(path, root))
                sources += f.endswith(".cpp")
                for number, line in enumerate(open(path, encoding="utf-8"), 1):
                    m = re.match(r'\s*#\s*include\s+"([^"]+)"', line)
                    if not m:
                        continue
                    header = m.group(1)
                    target = module_of(header[len("graspkit/"):] if header.startswith("graspkit/") else header)
                    count += 1
                    if target not in visible.get(owner, set()):
                        fail(f"{base}/{os.path.relpath(path, root)}:{number}: module {owner} includes "
                             f"{header} of module {target}, which it may not use")
    # Every .cpp includes at least its own header: fewer includes than sources means a missed walk.
    if sources < 50 or count < sources:
        fail(f"{count} includes in {sources} sources were read: the walk missed the engine")


def check_views(binary, compiler):
    views = os.path.join(binary, "engine", "module_views", "geometry")
    flags = ["-std=c++20", "-fsyntax-only", f"-I{views}/public", f"-I{views}/private",
             "-isystem", "/usr/include/eigen3"]
    with tempfile.TemporaryDirectory() as scratch:
        allowed = os.path.join(scratch, "allowed.cpp")
        with open(allowed, "w") as out:
            out.write('#include "graspkit/base/error.hpp"\n#include "graspkit/geometry/mesh.hpp"\n')
        run = subprocess.run([compiler, *flags, allowed], capture_output=True, text=True)
        if run.returncode != 0:
            fail(f"geometry's view refuses its own and base's headers:\n{run.stderr[:2000]}")
        back = os.path.join(scratch, "back_include.cpp")
        with open(back, "w") as out:
            out.write('#include "graspkit/model/world.hpp"\n')
        run = subprocess.run([compiler, *flags, back], capture_output=True, text=True)
        if run.returncode == 0:
            fail("a back-include (geometry -> model/world.hpp) compiled")
        elif "graspkit/model/world.hpp" not in run.stderr or not (
                "No such file" in run.stderr or "file not found" in run.stderr):  # GCC, clang
            fail(f"the back-include failed for another reason:\n{run.stderr[:2000]}")


def main():
    source, binary, compiler = sys.argv[1:4]
    modules = declared_modules(source)
    if len(modules) < 10:
        fail(f"engine/CMakeLists.txt declares {len(modules)} modules: the parse is broken")
    check_tables(source, modules)
    check_includes(source, modules)
    check_views(binary, compiler)
    check_unit_tests(source, modules)
    if failures:
        print(f"{len(failures)} layer check(s) failed")
        return 1
    print(f"layers: {len(modules)} modules agree in engine/CMakeLists.txt, docs/architecture.md, "
          "the folders and every include; a back-include fails to compile")
    return 0


if __name__ == "__main__":
    sys.exit(main())
