"""The Python module's cost beside the C++ calls it wraps, and its threads (issue 23's figures).

    PYTHONPATH=build/bindings/python /usr/bin/python3 bench/python_bench.py [--rays N] [--repeats R]

- rays: RayScene.intersect on N rays (NumPy in, NumPy out) against RayScene::intersect on the
  same rays in the same process (the rays converted beforehand, untimed): x_cpp = Python / C++.
- threads: plannerMug planned in two Python threads at once (threads=1 each) against the same
  two plans one after the other: speedup = sequential / parallel (2 cores: at most 2).
Min and median of R repeats.
"""

import argparse
import pathlib
import statistics
import sys
import threading
import time

import numpy as np

import graspkit

SHARED = pathlib.Path(__file__).resolve().parents[2] / "shared"


def timed(function, repeats):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return min(times), statistics.median(times)


def bench_rays(world_file, n, repeats):
    world = graspkit.load_world(world_file)
    scene = graspkit.RayScene(world)
    rng = np.random.default_rng(1)
    # From a sphere of 300 mm around the mug toward points near it: about half hit.
    origins = rng.normal(size=(n, 3))
    origins *= 300 / np.linalg.norm(origins, axis=1, keepdims=True)
    origins += (0, 0, 100)
    directions = (0, 0, 100) + rng.uniform(-80, 80, size=(n, 3)) - origins
    hits = scene.intersect(origins, directions)
    python = timed(lambda: scene.intersect(origins, directions), repeats)
    cpp = []
    for _ in range(repeats):
        cpp.append(scene._cpp_intersect_seconds(origins, directions))
    cpp = (min(cpp), statistics.median(cpp))
    print(f"rays: {n} rays, {hits.hit.mean():.0%} hit; Python {python[0] * 1e3:.1f}/"
          f"{python[1] * 1e3:.1f} ms, C++ {cpp[0] * 1e3:.1f}/{cpp[1] * 1e3:.1f} ms (min/median); "
          f"x_cpp {python[0] / cpp[0]:.3f} (min), {python[1] / cpp[1]:.3f} (median)")


def bench_threads(world_file, steps, repeats):
    def one(seed):
        graspkit.plan(graspkit.load_world(world_file), steps=steps, threads=1, seed=seed)

    def sequential():
        one(1)
        one(2)

    def parallel():
        workers = [threading.Thread(target=one, args=(s,)) for s in (1, 2)]
        for w in workers:
            w.start()
        for w in workers:
            w.join()

    seq = timed(sequential, repeats)
    par = timed(parallel, repeats)
    print(f"threads: two plans of {steps} steps, one after the other {seq[0]:.2f}/{seq[1]:.2f} s,"
          f" in two Python threads {par[0]:.2f}/{par[1]:.2f} s; speedup {seq[0] / par[0]:.2f} "
          f"(min), {seq[1] / par[1]:.2f} (median)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rays", type=int, default=1_000_000)
    parser.add_argument("--steps", type=int, default=20000)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--shared", type=pathlib.Path, default=SHARED)
    args = parser.parse_args()
    world_file = args.shared / "graspit-data/worlds/plannerMug.xml"
    if not world_file.exists():
        sys.exit(f"python_bench: {world_file} not found (--shared DIR)")
    bench_rays(world_file, args.rays, args.repeats)
    bench_threads(world_file, args.steps, args.repeats)


if __name__ == "__main__":
    main()
