"""graspkit batch's throughput as a dataset user feels it: held grasps per core-hour, for one
process, `--jobs J` and `mpirun -np R`, side by side on the same generated objects.

    python3 bench/batch_bench.py [--objects N] [--object-seed S] [--grasps G] [--steps STEPS]
                                 [--no-validate] [--statics] [--jobs J] [--ranks R] [--hand ROBOT.xml]
                                 [--repeats K] [--graspkit PROGRAM]

Generates N objects (`graspkit objects --generate N --seed S`), then runs `graspkit batch` on
them with the hand (default: GraspIt!'s Barrett from ../shared), G grasps per object, STEPS
planner steps and `--validate`, three ways in turn (K times each, interleaved, so that a drift
of the machine's speed touches all three alike):

  1 process   `--jobs 1`
  J jobs      `--jobs J` (default 2)
  R ranks     `mpirun -np R graspkit batch` (default 2; skipped when mpirun is missing)

For each it prints the held grasps (validation's label: every one of the 6 directions held),
the force-closure grasps, the CPU time of the whole command (graspkit and every process it
started: this process's children's rusage), the wall time, and held grasps per core-hour
(held / CPU hours): the figure issue 40 asks to raise tenfold. The three ways must write the
same datasets and manifest, byte for byte, which is checked.

The issue's figures were taken with `--objects 10 --object-seed 1` (24 held of 100 grasps, about
200 held per core-hour) and `--objects 6 --object-seed 11` (10 held of 60, 91 per CPU-hour).
`--graspkit` runs another build (e.g. one of an older commit) for a before/after pair;
`--statics` validates with `--validate-statics` (statics first, docs/dynamics.md).
"""

import argparse
import json
import os
import pathlib
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
GRASPKIT = ROOT / "build/apps/graspkit/graspkit"
BARRETT = ROOT.parent / "shared/graspit-data/models/robots/Barrett/Barrett.xml"


def children_cpu():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run(cmd, env):
    """Wall and CPU seconds of a command and everything it waited for."""
    cpu, start = children_cpu(), time.perf_counter()
    subprocess.run(cmd, check=True, env=env, stdout=subprocess.DEVNULL)
    return time.perf_counter() - start, children_cpu() - cpu


def files(folder):
    out = {p.name: p.read_bytes() for p in sorted((folder / "grasps").iterdir())}
    out["manifest.json"] = (folder / "manifest.json").read_bytes()
    return out


def counts(folder):
    manifest = json.loads((folder / "manifest.json").read_text())
    objects = manifest["objects"].values()
    failed = [o for o in objects if o.get("status") != "done"]
    if failed:
        sys.exit(f"batch failed on {len(failed)} objects: {failed[0].get('error')}")
    return (sum(o.get("grasps", 0) for o in objects), sum(o.get("force_closure", 0) for o in objects),
            sum(o.get("held", 0) for o in objects))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--objects", type=int, default=10)
    parser.add_argument("--object-seed", type=int, default=1)
    parser.add_argument("--grasps", type=int, default=10)
    parser.add_argument("--steps", type=int, default=40000)
    parser.add_argument("--no-validate", action="store_true")
    parser.add_argument("--statics", action="store_true")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--ranks", type=int, default=2)
    parser.add_argument("--hand", default=str(BARRETT))
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--graspkit", default=str(GRASPKIT))
    args = parser.parse_args()
    mpirun = shutil.which("mpirun")
    # Open MPI refuses to start as root without these (docs/dataset.md).
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    work = pathlib.Path(tempfile.mkdtemp(prefix="batch_bench_"))
    try:
        objects = work / "objects"
        subprocess.run([args.graspkit, "-q", "objects", "--generate", str(args.objects), "--seed",
                        str(args.object_seed), "--out", str(objects)], check=True)
        batch = [args.graspkit, "-q", "batch", "--hand", args.hand, "--objects", str(objects),
                 "--grasps", str(args.grasps), "--steps", str(args.steps)]
        if not args.no_validate:
            batch.append("--validate")
            if args.statics:
                batch.append("--validate-statics")
        ways = [("1 process", [], ["--jobs", "1"]),
                (f"{args.jobs} jobs", [], ["--jobs", str(args.jobs)])]
        if mpirun:
            ways.append((f"{args.ranks} MPI ranks", [mpirun, "-np", str(args.ranks)], []))
        else:
            print("mpirun is not installed (Debian openmpi-bin): MPI ranks skipped")
        results = {name: [] for name, _, _ in ways}
        reference = None
        for k in range(args.repeats):
            for name, prefix, jobs in ways:
                out = work / f"out_{len(results[name])}_{name.replace(' ', '_')}"
                wall, cpu = run(prefix + batch + jobs + ["--out", str(out)], env)
                written = files(out)
                if reference is None:
                    reference = written
                elif written != reference:
                    sys.exit(f"{name} wrote other files than the first run")
                results[name].append((wall, cpu, counts(out)))
                shutil.rmtree(out)
        print(f"{args.objects} objects (seed {args.object_seed}), hand "
              f"{pathlib.Path(args.hand).name}, {args.grasps} grasps and {args.steps} steps each"
              f"{'' if args.no_validate else ', validated'}"
              f"{', statics first' if args.statics and not args.no_validate else ''}; the same "
              f"files from every run")
        print(f"{'':14} {'grasps':>6} {'closure':>7} {'held':>5} {'CPU s':>8} {'wall s':>8} "
              f"{'held/core-hour':>15} {'objects/hour':>13}")
        for name, runs in results.items():
            wall = statistics.median(r[0] for r in runs)
            cpus = [r[1] for r in runs]
            cpu = statistics.median(cpus)
            grasps, closure, held = runs[0][2]
            per_core_hour = [held / (c / 3600.0) for c in cpus]
            spread = (f" ({min(per_core_hour):.0f}-{max(per_core_hour):.0f})"
                      if len(runs) > 1 else "")
            print(f"{name:14} {grasps:6d} {closure:7d} {held:5d} {cpu:8.1f} {wall:8.1f} "
                  f"{statistics.median(per_core_hour):9.0f}{spread:>6} "
                  f"{args.objects / wall * 3600:13.0f}")
    finally:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
