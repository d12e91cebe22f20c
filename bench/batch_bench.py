"""graspkit batch's throughput: objects per hour per core, one object at a time against MPI ranks
or against `--jobs J` objects at once.

    python3 bench/batch_bench.py [--objects N] [--steps S] [--ranks R | --jobs J]
                                 [--hand ROBOT.xml] [--repeats K]

Generates N objects (`graspkit objects --generate N --seed 7`), then plans them with the hand
(default: GraspIt!'s Barrett from ../shared) into a fresh folder, once with `--jobs 1` in one
process and once under `mpirun -np R` (or, with --jobs, in one process with `--jobs J`), K times
each in turn (paired, so a drift of the machine's speed does not bias the ratio). Prints
objects/hour per core for each and the median speedup (wall time of one at a time over R ranks or
J jobs; the issue asks >= 1.8 for 2). Every run's datasets and manifest must be the same files,
which is checked too.
"""

import argparse
import os
import pathlib
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
GRASPKIT = ROOT / "build/apps/graspkit/graspkit"
BARRETT = ROOT.parent / "shared/graspit-data/models/robots/Barrett/Barrett.xml"


def run(cmd, env=None):
    start = time.perf_counter()
    subprocess.run(cmd, check=True, env=env, stdout=subprocess.DEVNULL)
    return time.perf_counter() - start


def datasets(folder):
    files = {p.name: p.read_bytes() for p in sorted((folder / "grasps").iterdir())}
    files["manifest.json"] = (folder / "manifest.json").read_bytes()
    return files


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--objects", type=int, default=100)
    parser.add_argument("--steps", type=int, default=40000)
    parser.add_argument("--ranks", type=int, default=2)
    parser.add_argument("--jobs", type=int, help="compare --jobs 1 with --jobs J instead of MPI")
    parser.add_argument("--hand", default=str(BARRETT))
    parser.add_argument("--repeats", type=int, default=1)
    args = parser.parse_args()
    mpirun = shutil.which("mpirun")
    if not mpirun and not args.jobs:
        sys.exit("mpirun is not installed (Debian openmpi-bin)")
    parallel = args.jobs or args.ranks
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    work = pathlib.Path(tempfile.mkdtemp(prefix="batch_bench_"))
    try:
        objects = work / "objects"
        subprocess.run([str(GRASPKIT), "-q", "objects", "--generate", str(args.objects), "--seed",
                        "7", "--out", str(objects)], check=True)
        batch = ["-q", "batch", "--hand", args.hand, "--objects", str(objects), "--grasps", "20",
                 "--steps", str(args.steps)]
        one, many, reference = [], [], None
        for k in range(args.repeats):
            for ranks, times in ((1, one), (parallel, many)):
                out = work / f"out_{ranks}_{k}"
                prefix = [mpirun, "-np", str(ranks)] if ranks > 1 and not args.jobs else []
                jobs = ["--jobs", str(ranks)] if ranks == 1 or args.jobs else []
                times.append(run(prefix + [str(GRASPKIT)] + batch + jobs + ["--out", str(out)], env))
                files = datasets(out)
                if reference is None:
                    reference = files
                elif files != reference:
                    sys.exit(f"{ranks} ranks or jobs wrote other files than the first run")
        per_hour = lambda seconds, cores: args.objects / seconds * 3600 / cores
        print(f"{args.objects} objects, {args.steps} steps each, hand {pathlib.Path(args.hand).name}")
        print(f"1 process: {statistics.median(one):.1f} s, "
              f"{per_hour(statistics.median(one), 1):.0f} objects/hour/core")
        what = f"{parallel} jobs" if args.jobs else f"{parallel} ranks"
        print(f"{what}:   {statistics.median(many):.1f} s, "
              f"{per_hour(statistics.median(many), parallel):.0f} objects/hour/core")
        ratios = [a / b for a, b in zip(one, many)]
        print(f"speedup {statistics.median(ratios):.2f} (min {min(ratios):.2f}, "
              f"max {max(ratios):.2f}) with {what}")
    finally:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
