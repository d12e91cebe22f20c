#!/usr/bin/env python3
"""The parity test: one request through the five front ends gives the same answer.

The request (issue 39): plan plannerMug with a fixed seed and step budget; autograsp and measure
the hand where the world file puts it; validate one grasp; simulate a grasp world for 0.5 s with
the dynamic autograsp; plan one generated object's dataset (`graspkit objects` and `graspkit
batch` from the program; Lua, which reads datasets but does not plan them, reads the program's),
write it and read it back. Each front end (the graspkit program, a Lua script, Python, a C program,
a Rust program) runs it on its own with its own defaults for everything the request leaves out,
and reports plan, grasp, validation and simulation in one schema; the reports are compared field
by field against the program's. They share the engine, so they must agree to rounding: a front
end with a different default (mode, energy, threads, the hand or object it picks) or its own
reading of a setting shows up here.

Usage: parity_test.py GRASPKIT PYTHONPATH C_PROGRAM CARGO RUSTC LIB_DIR WORK_DIR SHARED_DIR
(CARGO may be "-" to leave Rust out, which the test then reports as a failure unless
GRASPKIT_PARITY_NO_RUST is set, as in the sanitizer build.)
"""

import json
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
STEPS, SEED, TOP, SECONDS = 3000, 7, 5, 0.5
TOLERANCE = 1e-9  # relative; the front ends run the same code, so only printing rounds
READ_DATASET = """
import json, sys, graspkit
def pose7(m):
    t, q = graspkit.translation_quaternion(m)
    return [float(v) for v in t] + [float(v) for v in q]
print(json.dumps([{"epsilon": g.epsilon, "volume": g.volume, "force_closure": g.force_closure,
                   "pose": pose7(g.pose)} for g in graspkit.load_dataset(sys.argv[1]).grasps]))
"""


def run(command, **kwargs):
    result = subprocess.run(command, capture_output=True, text=True, **kwargs)
    if result.returncode != 0:
        sys.exit(f"FAILED: {' '.join(map(str, command))} exited {result.returncode}\n"
                 f"{result.stdout}\n{result.stderr}")
    return result.stdout


def pose7(translation, quaternion):
    return list(translation) + list(quaternion)


def cli_dataset(graspkit, hand, out):
    """One generated object's dataset as `graspkit objects` and `graspkit batch` write it."""
    run([graspkit, "-q", "objects", "--generate", "1", "--seed", "2", "--out", out / "objects"])
    run([graspkit, "-q", "batch", "--hand", hand, "--objects", out / "objects", "--out",
         out / "dataset", "--grasps", "3", "--steps", "1500", "--seed", "5"])
    files = sorted((out / "dataset" / "grasps").glob("*.h5"))
    if len(files) != 1:
        sys.exit(f"FAILED: graspkit batch wrote {files} for one object")
    return files[0]


def cli_report(graspkit, world, root, grasp_world, work):
    common = ["--root", str(root)]
    plan = json.loads(run([graspkit, "-q", "plan", world, *common, "--steps", str(STEPS),
                           "--seed", str(SEED), "--top", str(TOP), "--json"]))
    grasps = [{"epsilon": g["epsilon"], "volume": g["volume"], "contacts": g["contacts"],
               "force_closure": g["force_closure"],
               "pose": pose7(g["closed_pose"]["world"]["translation"],
                             g["closed_pose"]["world"]["quaternion"])}
              for g in plan["grasps"]]
    grasp = json.loads(run([graspkit, "-q", "grasp", world, *common, "--autograsp", "--json"]))
    validation = json.loads(run([graspkit, "-q", "validate", grasp_world, *common,
                                 "--seconds", str(SECONDS), "--json"]))["grasps"][0]
    simulation = json.loads(run([graspkit, "-q", "simulate", grasp_world, *common,
                                 "--seconds", str(SECONDS), "--autograsp", "--json"]))
    return {
        "plan": grasps,
        "grasp": {"epsilon": grasp["epsilon"], "volume": grasp["volume"],
                  "contacts": len(grasp["contacts"]), "force_closure": grasp["force_closure"]},
        "validation": {"held": validation["held"],
                       "directions_held": validation["directions_held"],
                       "settle_seconds": validation["settle_seconds"],
                       "slip": [d["slip_mm"] for d in validation["directions"]]},
        "simulation": {"completed": simulation["completed"], "steps": simulation["steps"],
                       "time": simulation["time"],
                       "bodies": [pose7(b["position"], b["orientation_wxyz"])
                                  for b in simulation["bodies"]],
                       "dofs": [v for r in simulation["robots"] for v in r["dof_values"]]},
    }


def canonical(value):
    """A pose's quaternion with w >= 0 (q and -q are one rotation)."""
    if isinstance(value, list) and len(value) == 7 and all(isinstance(v, float) for v in value):
        if value[3] < 0:
            return value[:3] + [-v for v in value[3:]]
    return value


def compare(expected, got, where, problems):
    expected, got = canonical(expected), canonical(got)
    if isinstance(expected, dict):
        if set(expected) != set(got):
            problems.append(f"{where}: keys {sorted(got)} instead of {sorted(expected)}")
            return
        for key in expected:
            compare(expected[key], got[key], f"{where}.{key}", problems)
    elif isinstance(expected, list):
        if not isinstance(got, list) or len(expected) != len(got):
            problems.append(f"{where}: {got!r} instead of {expected!r}")
            return
        for i, (e, g) in enumerate(zip(expected, got)):
            compare(e, g, f"{where}[{i}]", problems)
    elif isinstance(expected, bool) or isinstance(got, bool):
        if expected != got:
            problems.append(f"{where}: {got!r} instead of {expected!r}")
    elif isinstance(expected, (int, float)):
        if not isinstance(got, (int, float)) or not math.isclose(
                expected, got, rel_tol=TOLERANCE, abs_tol=1e-9):
            problems.append(f"{where}: {got!r} instead of {expected!r}")
    elif expected != got:
        problems.append(f"{where}: {got!r} instead of {expected!r}")


def main():
    graspkit, pythonpath, c_program, cargo, rustc, lib_dir, work, shared = sys.argv[1:9]
    work = Path(work)
    work.mkdir(parents=True, exist_ok=True)
    root = Path(shared) / "graspit-data"
    world = root / "worlds" / "plannerMug.xml"
    if not world.is_file():
        print(f"graspkit: SKIPPED: GraspIt!'s corpus is not at {root}")
        return 0

    # The grasp to validate and simulate: the program's best plannerMug grasp, saved. Every
    # front end loads this one file.
    run([graspkit, "-q", "plan", world, "--root", root, "--steps", "2000", "--seed", "3",
         "--top", "1", "--out", work / "held.json"])
    grasp_world = work / "held_01.xml"
    hand = HERE.parents[1] / "models" / "robots" / "parallel_jaw" / "parallel_jaw.xml"
    args = [str(world), str(root), str(grasp_world), str(STEPS), str(SEED), str(TOP),
            str(SECONDS), str(hand)]

    def out(name):  # each front end's own folder for the files it writes
        folder = work / name
        shutil.rmtree(folder, ignore_errors=True)
        folder.mkdir()
        return folder

    env = dict(os.environ, PYTHONPATH=pythonpath, PYTHONDONTWRITEBYTECODE="1")
    reports = {"cli": cli_report(graspkit, str(world), root, str(grasp_world), work)}
    cli_h5 = cli_dataset(graspkit, hand, out("cli"))
    # The program's dataset, read with the Python module's reader (each front end's own reader
    # is checked on the file it wrote itself).
    reports["cli"]["dataset"] = json.loads(run(
        [sys.executable, "-c", READ_DATASET, str(cli_h5)], env=env))
    reports["lua"] = json.loads(run(
        [graspkit, "-q", "run", HERE / "parity.lua", "--json", "--root", root, "--allow-read",
         work, "--", args[0], args[2], *args[3:7], str(cli_h5)]))
    reports["python"] = json.loads(run([sys.executable, HERE / "parity.py", *args,
                                        str(out("python"))], env=env))
    reports["c"] = json.loads(run([c_program, *args, str(out("c"))]))
    if cargo != "-":
        manifest = Path(__file__).resolve().parents[2] / "bindings" / "rust" / "Cargo.toml"
        rust_env = dict(os.environ, GRASPKIT_LIB_DIR=lib_dir, RUSTC=rustc,
                        CARGO_TARGET_DIR=str(work / "rust_target"),
                        CARGO_HOME=str(work / "rust_target" / "cargo-home"))
        reports["rust"] = json.loads(run(
            [cargo, "run", "--offline", "--quiet", "--manifest-path", manifest, "--example",
             "parity", "--", *args, str(out("rust"))], env=rust_env))
    elif not os.environ.get("GRASPKIT_PARITY_NO_RUST"):
        sys.exit("FAILED: no cargo given: the Rust crate was not compared")

    expected = reports["cli"]
    if len(expected["plan"]) != TOP:
        sys.exit(f"FAILED: graspkit plan kept {len(expected['plan'])} grasps, not {TOP}")
    problems = []
    for name, report in reports.items():
        compare(expected, report, name, problems)
    (work / "reports.json").write_text(json.dumps(reports, indent=1))
    if problems:
        print("\n".join(problems))
        sys.exit(f"FAILED: {len(problems)} field(s) differ from graspkit's (all reports: "
                 f"{work / 'reports.json'})")
    print(f"the {len(reports)} front ends agree on {len(expected['plan'])} planned grasps, the "
          f"autograsp's measure, the validation and the simulation: {', '.join(reports)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
