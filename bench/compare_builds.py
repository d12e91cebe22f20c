"""Two builds' benchmark rows, run in turn on one core, with each round's ratio.

    python3 bench/compare_builds.py --old OLD_BUILD [--new NEW_BUILD] [--rounds N] [--core C]
                                    [--bench NAME=FILTER ...]

`x_graspit` divides GraspIt!'s time, measured once (../shared/reference), by ours, measured now;
it therefore moves with the machine's speed as much as with the code. That speed moves a lot
where the machine is shared: the same binary has run its collision report in 16.7 us one day and
41.7 us another, and within one hour by 20-30 %. A change is judged by running the build before
it and the build after it in turn, in one command, and by each round's old/new ratio, which a
drift of the machine touches on both sides alike.

Build the other commit in its own folder first, for example:

    git worktree add ../before COMMIT && cmake -S ../before -B ../before/build -G Ninja \\
        -DCMAKE_BUILD_TYPE=Release && cmake --build ../before/build --target grasp_bench \\
        collision_bench planner_bench graspkit_plugins

Each round runs every bench of OLD_BUILD, then of NEW_BUILD (default: build/ of this checkout),
pinned to core C (default 1) with taskset, each with the robot plugins of its own build. It
prints, for every row both builds have, min/median/max over the rounds of the old time, the new
time and the old/new ratio (above 1: the new build is faster), and the new build's x_graspit.
An old build's row that a later build renamed or changed is simply not in both, so it is left
out; check that the rows compared measure the same work in both commits.
"""

import argparse
import json
import os
import pathlib
import shutil
import statistics
import subprocess
import sys

DEFAULT_BENCHES = [
    "grasp_bench=BM_Contacts$|BM_CollisionReport|BM_AutoGraspOnly",
    "collision_bench=BM_CollisionReport|BM_CollideLinkMug",
    "planner_bench=Plan/",
]


def run_bench(build, name, bench_filter, core):
    """One run of one benchmark program: {row name: (real time, unit, x_graspit or None)}."""
    program = build / "bench" / name
    if not program.exists():
        sys.exit(f"compare_builds: {program} does not exist; build the target {name} there first")
    env = dict(os.environ, GRASPKIT_PLUGIN_PATH=str(build / "plugins"))
    command = [str(program), f"--benchmark_filter={bench_filter}", "--benchmark_format=json"]
    if core is not None:
        command = ["taskset", "-c", str(core)] + command
    run = subprocess.run(command, env=env, capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"compare_builds: {' '.join(command)} failed:\n{run.stderr[-2000:]}")
    rows = {}
    for row in json.loads(run.stdout)["benchmarks"]:
        if row.get("error_occurred"):
            continue
        rows[f"{name}:{row['name']}"] = (row["real_time"], row["time_unit"], row.get("x_graspit"))
    return rows


def spread(values):
    ordered = sorted(values)
    return f"{ordered[0]:.4g}/{statistics.median(ordered):.4g}/{ordered[-1]:.4g}"


def main():
    root = pathlib.Path(__file__).resolve().parent.parent
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--old", required=True, type=pathlib.Path, help="the build before")
    parser.add_argument("--new", type=pathlib.Path, default=root / "build", help="the build after")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--core", type=int, default=1, help="core to pin to; -1: not pinned")
    parser.add_argument("--bench", action="append", metavar="NAME=FILTER",
                        help="a benchmark program and its --benchmark_filter (repeatable)")
    args = parser.parse_args()
    if args.rounds < 1:
        parser.error("--rounds must be at least 1")
    core = None if args.core < 0 else args.core
    if core is not None and not shutil.which("taskset"):
        parser.error("taskset is missing (Debian util-linux); pass --core -1 to run unpinned")
    benches = []
    for spec in args.bench or DEFAULT_BENCHES:
        name, sep, bench_filter = spec.partition("=")
        if not sep or not name:
            parser.error(f"--bench {spec!r}: expected NAME=FILTER, e.g. grasp_bench=BM_Contacts")
        benches.append((name, bench_filter))

    times = {"old": {}, "new": {}}  # side -> row -> {round: (time, unit, x_graspit)}
    for round_index in range(args.rounds):
        for side, build in (("old", args.old), ("new", args.new)):
            for name, bench_filter in benches:
                for row, value in run_bench(build.resolve(), name, bench_filter, core).items():
                    times[side].setdefault(row, {})[round_index] = value
        print(f"round {round_index + 1} of {args.rounds} done", file=sys.stderr)

    print(f"old: {args.old}\nnew: {args.new}\n{args.rounds} rounds, min/median/max")
    print(f"{'row':58s} {'old':>24s} {'new':>24s} {'old/new':>17s} {'new x_graspit':>17s}")
    for row in sorted(set(times["old"]) & set(times["new"])):
        rounds = sorted(set(times["old"][row]) & set(times["new"][row]))  # pairs of one round
        old = [times["old"][row][r] for r in rounds]
        new = [times["new"][row][r] for r in rounds]
        unit = new[0][1]
        ratios = [o[0] / n[0] for o, n in zip(old, new)]
        graspit = [n[2] for n in new if n[2] is not None]
        print(f"{row[:58]:58s} {spread([o[0] for o in old]) + ' ' + unit:>24s} "
              f"{spread([n[0] for n in new]) + ' ' + unit:>24s} {spread(ratios):>17s} "
              f"{spread(graspit) if graspit else '-':>17s}")


if __name__ == "__main__":
    main()
