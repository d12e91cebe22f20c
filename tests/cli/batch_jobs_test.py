#!/usr/bin/env python3
"""`graspkit batch --jobs N`: N objects at once on one machine, the same files as one at a time.

Usage: batch_jobs_test.py GRASPKIT SOURCE_DIR WORK_DIR [sanitize]

With `sanitize` (the ASan/UBSan build) the mpirun check is skipped, as in batch_test.py.

On a few generated objects (and a broken one) with a tiny budget, each against an independent
truth (the bytes of a `--jobs 1` run, the process table):
  - `--jobs 2` and `--jobs 3` write the same manifest and datasets as `--jobs 1`, byte for byte,
    the broken object's failure included; only timings.json may differ, and it lists every object;
  - `--jobs 2` has two objects' processes running at once, and never more; `--jobs 1` never more
    than one;
  - a `--jobs 2` run killed mid-way and run again ends with the `--jobs 1` datasets and manifest,
    each good object attempted once (the broken one may have been retried);
  - `--jobs 0`, `--jobs -1` and `--jobs x` are usage errors (exit 2), not crashes; under mpirun
    `--jobs 2` is refused.
"""

import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

GRASPKIT, SOURCE, WORK = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3])
SANITIZE = len(sys.argv) > 4 and sys.argv[4] == "sanitize"
HAND = SOURCE / "models/robots/parallel_jaw/parallel_jaw.xml"
COUNT = 5


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def command(out, jobs):
    return [GRASPKIT, "-q", "batch", "--hand", str(HAND), "--objects", str(listing), "--out",
            str(out), "--grasps", "3", "--steps", "3000", "--jobs", str(jobs)]


def files(out):
    """Every file the run wrote but timings.json, by path relative to the folder."""
    return {str(p.relative_to(out)): p.read_bytes() for p in sorted(Path(out).rglob("*"))
            if p.is_file() and p.name != "timings.json"}


def children(pid):
    try:
        return len(Path(f"/proc/{pid}/task/{pid}/children").read_text().split())
    except OSError:
        return 0


def run_watched(out, jobs):
    """Runs a batch; returns (exit status, the most object processes seen at once)."""
    process = subprocess.Popen(command(out, jobs), stdout=subprocess.DEVNULL,
                               stderr=subprocess.PIPE, text=True)
    most = 0
    while process.poll() is None:
        most = max(most, children(process.pid))
        time.sleep(0.002)
    process.stderr.read()
    return process.returncode, most


if WORK.exists():
    shutil.rmtree(WORK)
WORK.mkdir(parents=True)
objects = WORK / "objects"
subprocess.run([GRASPKIT, "-q", "objects", "--generate", str(COUNT), "--seed", "3", "--out",
                str(objects)], check=True)
(WORK / "broken.xml").write_text("<root><material>plastic</material><mass>oops</mass></root>\n")
names = [line.split()[0] for line in (objects / "objects.txt").read_text().splitlines()
         if line.strip() and not line.startswith("#")]
listing = WORK / "objects.txt"  # a broken object among the good ones
listing.write_text("".join(f"objects/{n}\n" for n in names[:2]) + "broken.xml\n" +
                   "".join(f"objects/{n}\n" for n in names[2:]))

reference_out = WORK / "jobs1"
status, most = run_watched(reference_out, 1)
if status != 1:  # the broken object fails the run
    fail(f"--jobs 1 exited {status}")
if most != 1:
    fail(f"--jobs 1 ran {most} objects' processes at once")
reference = files(reference_out)
entries = json.loads(reference["manifest.json"])["objects"]
if sorted(e["status"] for e in entries.values()) != ["done"] * COUNT + ["failed"]:
    fail(f"the --jobs 1 run did not do the objects and fail the broken one: {entries}")
if any("seconds" in e for e in entries.values()):
    fail(f"the manifest holds wall times: {entries}")

for jobs in (2, 3):
    out = WORK / f"jobs{jobs}"
    status, most = run_watched(out, jobs)
    if status != 1:
        fail(f"--jobs {jobs} exited {status}")
    if jobs == 2 and most != 2:
        fail(f"--jobs 2 ran at most {most} objects' processes at once, not 2")
    if most > jobs:
        fail(f"--jobs {jobs} ran {most} objects' processes at once")
    got = files(out)
    differ = sorted(n for n in set(got) | set(reference) if got.get(n) != reference.get(n))
    if differ:
        fail(f"--jobs {jobs} wrote other files than --jobs 1: {differ}")
    timings = json.loads((out / "timings.json").read_text())["objects"]
    if sorted(timings) != sorted(entries) or any(t["seconds"] <= 0 for t in timings.values()):
        fail(f"timings.json does not time every object: {timings}")

# Killed mid-way with two objects in flight, then run again with --jobs 2.
killed = WORK / "killed"
process = subprocess.Popen(command(killed, 2), start_new_session=True,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
deadline = time.time() + 60
while time.time() < deadline and process.poll() is None:
    try:
        manifest = json.loads((killed / "manifest.json").read_text())
        done = sum(e.get("status") == "done" for e in manifest["objects"].values())
    except (FileNotFoundError, json.JSONDecodeError, KeyError):
        done = 0
    if done >= 1 and children(process.pid) >= 1:
        break
    time.sleep(0.002)
if process.poll() is not None:
    fail("the --jobs 2 run ended before it could be killed")
os.killpg(process.pid, signal.SIGKILL)
process.wait()
rerun = subprocess.run(command(killed, 2), capture_output=True, text=True)
if rerun.returncode != 1 or "already settled" not in rerun.stdout:
    fail(f"the killed run did not resume ({rerun.returncode}): {rerun.stdout}{rerun.stderr}")
got = files(killed)
differ = sorted(n for n in set(got) | set(reference)
                if n != "manifest.json" and got.get(n) != reference.get(n))
if differ:
    fail(f"a killed and resumed --jobs 2 run wrote other datasets than --jobs 1: {differ}")
# The broken object may have failed before the kill, and then been retried once: the rest of
# the manifest is the --jobs 1 run's, each object attempted once.
resumed = json.loads(got["manifest.json"])
broken_entry = resumed["objects"].pop("broken")
expected = json.loads(reference["manifest.json"])
expected_broken = expected["objects"].pop("broken")
if resumed != expected or broken_entry["attempts"] not in (1, 2) or \
        {k: v for k, v in broken_entry.items() if k != "attempts"} != \
        {k: v for k, v in expected_broken.items() if k != "attempts"}:
    fail(f"the resumed manifest is not the --jobs 1 run's: {resumed} {broken_entry}")

for bad in ("0", "-1", "x"):
    run = subprocess.run(command(WORK / "bad", 1)[:-1] + [bad], capture_output=True, text=True)
    if run.returncode != 2 or "--jobs" not in run.stderr:
        fail(f"--jobs {bad} gave exit {run.returncode}: {run.stderr}")
# Under mpirun each rank plans one object at a time: --jobs 2 is refused, not multiplied.
mpirun = shutil.which("mpirun")
if mpirun and not SANITIZE:
    run = subprocess.run([mpirun, "--allow-run-as-root", "-np", "1"] + command(WORK / "mpi", 2),
                         capture_output=True, text=True, timeout=120)
    if run.returncode == 0 or "--jobs: under mpirun" not in run.stderr:
        fail(f"mpirun with --jobs 2 gave exit {run.returncode}: {run.stderr}")
else:
    print("SKIPPED the mpirun check: mpirun is not installed, or the sanitizer build")
print("batch --jobs: every check passed")
