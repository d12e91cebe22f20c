#!/usr/bin/env python3
"""`graspkit batch` as a user runs it, on generated objects and the project's parallel jaw.

Usage: batch_test.py GRASPKIT SOURCE_DIR WORK_DIR

Checks, each against an independent truth (a single uninterrupted run, the body files, h5py):
  - one run plans every object once: a dataset per object, the manifest says done;
  - running again changes nothing (every file keeps its bytes);
  - two shards into one folder give the same files as the single run;
  - a run killed with SIGKILL mid-way, then run again, ends with the same files, each object
    attempted once, and no temporaries left;
  - a broken object file is recorded as failed with its name and reason, the rest finish, it is
    retried once and then left alone;
  - an object that runs out of time is killed and recorded as failed;
  - h5py reads the files: transforms are rigid, the force-closure count is the manifest's, the
    object's mass is its Body XML's.
"""

import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

GRASPKIT, SOURCE, WORK = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3])
HAND = SOURCE / "models/robots/parallel_jaw/parallel_jaw.xml"
COUNT = 6


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def batch(objects, out, *extra, check=True):
    cmd = [GRASPKIT, "-q", "batch", "--hand", str(HAND), "--objects", str(objects), "--out",
           str(out), "--grasps", "3", "--steps", "1500", *extra]
    run = subprocess.run(cmd, capture_output=True, text=True)
    if check and run.returncode != 0:
        fail(f"{' '.join(cmd)} exited {run.returncode}: {run.stdout}{run.stderr}")
    return run


def datasets(out):
    folder = Path(out) / "grasps"
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())}


def manifest(out, name="manifest.json"):
    return json.loads((Path(out) / name).read_text())


if WORK.exists():
    shutil.rmtree(WORK)
WORK.mkdir(parents=True)
objects = WORK / "objects"
subprocess.run([GRASPKIT, "-q", "objects", "--generate", str(COUNT), "--seed", "5", "--out",
                str(objects)], check=True)

# One run, then the same command again.
single = WORK / "single"
batch(objects, single)
files = datasets(single)
if sorted(files) != sorted(f"object_{i:04d}_{k}.h5" for i, k in
                           zip(range(COUNT), ["box", "cylinder", "sphere", "superquadric",
                                              "convex_hull", "box"])):
    fail(f"the datasets are {sorted(files)}")
entries = manifest(single)["objects"]
if len(entries) != COUNT or any(e["status"] != "done" or e["attempts"] != 1
                                for e in entries.values()):
    fail(f"the manifest does not say every object was done once: {entries}")
again = batch(objects, single)
if "already settled" not in again.stdout or datasets(single) != files:
    fail(f"running again changed something: {again.stdout}")

# Two shards into one folder.
sharded = WORK / "sharded"
batch(objects, sharded, "--shard", "1/2")
batch(objects, sharded, "--shard", "2/2")
if datasets(sharded) != files:
    fail("two shards did not give the single run's files")
shard_entries = {**manifest(sharded, "manifest-1-of-2.json")["objects"],
                 **manifest(sharded, "manifest-2-of-2.json")["objects"]}
if sorted(shard_entries) != sorted(entries):
    fail(f"the shards' manifests do not cover the objects once: {sorted(shard_entries)}")

# Killed mid-way, then resumed.
killed = WORK / "killed"
cmd = [GRASPKIT, "-q", "batch", "--hand", str(HAND), "--objects", str(objects), "--out",
       str(killed), "--grasps", "3", "--steps", "1500"]
process = subprocess.Popen(cmd, start_new_session=True, stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL)
deadline = time.time() + 120
while time.time() < deadline:
    try:
        done = sum(e.get("status") == "done" for e in manifest(killed)["objects"].values())
    except (FileNotFoundError, json.JSONDecodeError, KeyError):
        done = 0
    if done >= 2 or process.poll() is not None:
        break
    time.sleep(0.02)
if process.poll() is not None:
    fail("the run ended before it could be killed; the test needs more objects or steps")
os.killpg(process.pid, signal.SIGKILL)
process.wait()
batch(objects, killed)
if datasets(killed) != files:
    fail("a killed and resumed run did not give the single run's files")
if any(e["attempts"] != 1 for e in manifest(killed)["objects"].values()):
    fail(f"an object was attempted twice: {manifest(killed)['objects']}")

# A broken object among good ones: failed with a reason, retried once, then left alone.
listing = WORK / "with_broken.txt"
(WORK / "broken.xml").write_text("<root><material>plastic</material><mass>oops</mass></root>\n")
listing.write_text("objects/object_0000_box.xml\nbroken.xml  # a mass that is not a number\n"
                   "objects/object_0001_cylinder.xml\n")
broken = WORK / "broken"
run = batch(listing, broken, check=False)
entry = manifest(broken)["objects"]["broken"]
if run.returncode != 1 or entry["status"] != "failed" or "broken.xml" not in entry["error"]:
    fail(f"the broken object was not recorded as failed with its file: {run.stdout} {entry}")
if sorted(datasets(broken)) != ["object_0000_box.h5", "object_0001_cylinder.h5"]:
    fail(f"the good objects did not finish: {sorted(datasets(broken))}")
batch(listing, broken, check=False)
batch(listing, broken, check=False)
if manifest(broken)["objects"]["broken"]["attempts"] != 2:
    fail(f"the broken object was not retried exactly once: {manifest(broken)['objects']}")

# Out of time: killed and recorded.
slow = WORK / "slow"
run = batch(objects, slow, "--object-timeout", "0.001", check=False)
statuses = {e["status"] for e in manifest(slow)["objects"].values()}
errors = {e.get("error", "") for e in manifest(slow)["objects"].values()}
if run.returncode != 1 or statuses != {"failed"} or not all("timed out" in e for e in errors):
    fail(f"objects out of time were not failed as timed out: {statuses} {errors}")

# Read with h5py, an independent reader.
try:
    import h5py
    import numpy
except ImportError:
    print("SKIPPED the h5py checks: python3-h5py is not installed (scripts/dev installs it)")
    sys.exit(0)
for name, entry in entries.items():
    with h5py.File(single / "grasps" / f"{name}.h5", "r") as f:
        transforms = f["grasps/transforms"][()]
        if transforms.shape != (3, 4, 4):
            fail(f"{name}: transforms of shape {transforms.shape}")
        for t in transforms:
            r = t[:3, :3]
            if not numpy.allclose(r @ r.T, numpy.eye(3), atol=1e-9) or list(t[3]) != [0, 0, 0, 1]:
                fail(f"{name}: a transform is not rigid: {t}")
        fc = int(f["grasps/qualities/force_closure"][()].sum())
        if fc != entry["force_closure"]:
            fail(f"{name}: {fc} force-closure grasps in the file, {entry['force_closure']} listed")
        body = (objects / f"{name}.xml").read_text()
        mass = float(re.search(r"<mass>([^<]+)</mass>", body).group(1))
        if abs(f["object/mass"][()] - mass) > 1e-9 * mass:
            fail(f"{name}: mass {f['object/mass'][()]} in the file, {mass} in the body XML")
        if f.attrs["units"] != "mm" or f["hand/name"][()].decode() != "parallel_jaw":
            fail(f"{name}: units {f.attrs['units']}, hand {f['hand/name'][()]}")
print("batch: every check passed")
