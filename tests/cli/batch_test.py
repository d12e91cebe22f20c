#!/usr/bin/env python3
"""`graspkit batch` as a user runs it, on generated objects and the project's parallel jaw.

Usage: batch_test.py GRASPKIT SOURCE_DIR WORK_DIR [sanitize]

With `sanitize` (the ASan/UBSan build) the MPI checks are skipped: Open MPI's own allocations
would fail the leak checker in every rank.

Checks, each against an independent truth (a single uninterrupted run, the body files, h5py):
  - one run (`--jobs 1`) plans every object once: a dataset per object, the manifest says done;
    the other runs (the default --jobs: the cores) must give its files;
  - running again changes nothing (every file keeps its bytes);
  - two shards into one folder give the same files as the single run;
  - a run killed with SIGKILL mid-way, then run again, ends with the same files, each object
    attempted once, and no temporaries left (a dead writer's manifest or timings copy is
    removed, a running one's is not);
  - a broken object file is recorded as failed with its name and reason, the rest finish, it is
    retried once and then left alone;
  - an object that runs out of time is killed and recorded as failed;
  - h5py reads the files: transforms are rigid, the force-closure count is the manifest's, the
    object's mass is its Body XML's, force closure is epsilon >= 1e-6, the object and hand files
    are named from the dataset's folder;
  - a validated batch keeps each direction's result, consistent with the grasp's label and with
    validation's limits;
  - a dataset read as frames (validate, export, render): each grasp put back into a world from
    the file validates again to the batch's figures in every direction, and its glTF scene
    carries the file's epsilon and contacts; a grasp number out of range, or an object file
    changed since, is refused;
  - the load flags that change the hand (--close here) are settings the manifest records.
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
SANITIZE = len(sys.argv) > 4 and sys.argv[4] == "sanitize"
HAND = SOURCE / "models/robots/parallel_jaw/parallel_jaw.xml"
COUNT = 20  # the MPI check: 20 objects
KINDS = ["box", "cylinder", "sphere", "superquadric", "convex_hull"]


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


def differences(out):
    """Names of the files in out/grasps that are missing, extra or not the single run's bytes."""
    got = datasets(out)
    return sorted(n for n in set(got) | set(files) if got.get(n) != files.get(n))


def manifest(out, name="manifest.json"):
    return json.loads((Path(out) / name).read_text())


if WORK.exists():
    shutil.rmtree(WORK)
WORK.mkdir(parents=True)
objects = WORK / "objects"
subprocess.run([GRASPKIT, "-q", "objects", "--generate", str(COUNT), "--seed", "5", "--out",
                str(objects)], check=True)

# One run, one object at a time (the runs below plan as many at once as there are cores), then the
# same command again.
single = WORK / "single"
batch(objects, single, "--jobs", "1")
files = datasets(single)
if sorted(files) != sorted(f"object_{i:04d}_{KINDS[i % 5]}.h5" for i in range(COUNT)):
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
merged = manifest(sharded)
if merged["objects"] != shard_entries or len(merged["merged_from"]) != 2:
    fail(f"manifest.json does not gather the two shards: {merged}")
run = batch(objects, sharded)  # unsharded, same settings: resumes from the merged manifest
if f"{COUNT} already settled" not in run.stdout or datasets(sharded) != files:
    fail(f"a run without --shard did not resume from the merged manifest: {run.stdout}")

# A dataset marked done but truncated is planned again on resume, not kept.
victim = sorted((sharded / "grasps").glob("*.h5"))[0]
victim.write_bytes(victim.read_bytes()[:100])
run = batch(objects, sharded)
if f"{COUNT - 1} already settled" not in run.stdout:
    fail(f"a truncated dataset was kept as done: {run.stdout}")
if differences(sharded):
    fail(f"the re-planned dataset is not the single run's: {differences(sharded)}")

# A tampered manifest (a number where a status belongs) is bad input: exit 1, not 3.
tampered = WORK / "tampered"
shutil.copytree(sharded, tampered)
data = json.loads((tampered / "manifest.json").read_text())
next(iter(data["objects"].values()))["status"] = 5
(tampered / "manifest.json").write_text(json.dumps(data))
run = batch(objects, tampered, check=False)
if run.returncode != 1 or "not a batch manifest" not in run.stderr:
    fail(f"a tampered manifest gave exit {run.returncode}: {run.stderr}")

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
    if done >= 1 or process.poll() is not None:
        break
    time.sleep(0.01)
if process.poll() is not None:
    fail("the run ended before it could be killed; the test needs more objects or steps")
os.killpg(process.pid, signal.SIGKILL)
process.wait()
# A writer's leftover from another machine of a cluster: its process id (1) runs here, so only the
# rule that a finished object's temporaries are stale can clear it.
pending_names = [f"object_{i:04d}_{KINDS[i % 5]}" for i in range(COUNT)
                 if manifest(killed)["objects"].get(f"object_{i:04d}_{KINDS[i % 5]}", {})
                 .get("status") != "done"]
leftover = killed / "grasps" / f".{pending_names[-1]}.h5.1.tmp"
leftover.write_bytes(b"half a dataset")
# A manifest and a timings file whose writer was killed between naming its copy and renaming it
# over the file (a process that has ended), and one whose writer still runs (this test).
ended = subprocess.Popen(["true"])
ended.wait()
stale = [killed / f"manifest.json.tmp{ended.pid}", killed / f"timings.json.tmp{ended.pid}"]
live = killed / f"timings.json.tmp{os.getpid()}"
for f in stale + [live]:
    f.write_text("{")
batch(objects, killed)
if datasets(killed) != files:
    fail("a killed and resumed run did not give the single run's files")
if any(f.exists() for f in stale) or not live.exists():
    fail(f"the resumed run did not clear its dead writers' temporaries alone: "
         f"{sorted(p.name for p in killed.iterdir())}")
live.unlink()
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

# Over MPI: two ranks share the objects; a rank killed mid-run, and the run again, completes the
# set. Both must give the single run's files.
mpirun = shutil.which("mpirun")
if SANITIZE:
    print("SKIPPED the MPI checks in the sanitizer build (Open MPI's allocations)")
elif not mpirun:
    print("SKIPPED the MPI checks: mpirun is not installed (scripts/dev installs openmpi-bin)")
else:
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_btl_base_warn_component_unused="0")
    mpi_cmd = [mpirun, "-np", "2", "--oversubscribe", GRASPKIT, "-q", "batch", "--hand", str(HAND),
               "--objects", str(objects), "--grasps", "3", "--steps", "1500"]
    ranks = WORK / "mpi"
    run = subprocess.run(mpi_cmd + ["--out", str(ranks)], capture_output=True, text=True, env=env,
                         timeout=300)
    if run.returncode != 0 or datasets(ranks) != files:
        fail(f"mpirun -np 2 did not give the single run's files ({run.returncode}): "
             f"{run.stdout}{run.stderr}")
    if any(e["attempts"] != 1 or e["status"] != "done" for e in manifest(ranks)["objects"].values()):
        fail(f"mpirun -np 2 did not do every object once: {manifest(ranks)['objects']}")

    killed_mpi = WORK / "mpi_killed"
    process = subprocess.Popen(mpi_cmd + ["--out", str(killed_mpi)], start_new_session=True,
                               env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.time() + 120
    while time.time() < deadline and process.poll() is None:
        try:
            done = sum(e.get("status") == "done" for e in manifest(killed_mpi)["objects"].values())
        except (FileNotFoundError, json.JSONDecodeError, KeyError):
            done = 0
        if done >= 1:
            break
        time.sleep(0.01)
    if process.poll() is not None:
        fail("the MPI run ended before a rank could be killed")
    children = subprocess.run(["pgrep", "-P", str(process.pid)], capture_output=True,
                              text=True).stdout.split()
    if not children:
        fail("no rank processes were found under mpirun")
    os.kill(int(children[-1]), signal.SIGKILL)  # one rank
    try:
        process.wait(timeout=60)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        process.wait()
    run = subprocess.run(mpi_cmd + ["--out", str(killed_mpi)], capture_output=True, text=True,
                         env=env, timeout=300)
    if run.returncode != 0 or datasets(killed_mpi) != files:
        fail(f"after a rank was killed, running again did not complete the set ({run.returncode}):"
             f" {run.stdout}{run.stderr}; files that differ (a stray temporary among them means a "
             f"killed rank's writer was not cleaned up): {differences(killed_mpi)}")
    if any(e["status"] != "done" for e in manifest(killed_mpi)["objects"].values()):
        fail(f"objects are missing after the resumed MPI run: {manifest(killed_mpi)['objects']}")

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
        # Force closure is epsilon >= 1e-6 (docs/dataset.md), never a rounding's sign.
        epsilon = f["grasps/qualities/epsilon"][()]
        flags = f["grasps/qualities/force_closure"][()]
        if [int(x) for x in flags] != [int(e >= 1e-6) for e in epsilon]:
            fail(f"{name}: force_closure {list(flags)} for epsilons {list(epsilon)}")
        # The files are named relative to the dataset's folder (or absolutely): they are found
        # from wherever the dataset is read.
        folder = single / "grasps"
        for key, expected in (("object/file", objects / f"{name}.xml"), ("hand/file", HAND)):
            named = folder / f[key][()].decode()
            if not named.exists() or not named.samefile(expected):
                fail(f"{name}: {key} is {f[key][()].decode()}, which is not {expected} from {folder}")
        if f["grasps/validation/held"][()].tolist() != [[-1] * 6] * len(epsilon):
            fail(f"{name}: not validated, yet grasps/validation/held is {f['grasps/validation/held'][()]}")

# A validated batch keeps each direction's result: held in all six exactly when the grasp is
# held, and a direction held exactly when the object stayed within validation's limits (5 mm of
# slip, 15 degrees of turn) and the simulation did not fail. By default a grasp's validation ends
# at the first direction it lets go (the others -1: not tried), so a grasp not held has exactly
# one direction let go; --validate-all-directions tries all six, and the two must agree on every
# label and on every direction both tried.
(WORK / "two.txt").write_text("objects/object_0000_box.xml\nobjects/object_0001_cylinder.xml\n")


def validated_batch(folder, *flags):
    run = subprocess.run([GRASPKIT, "-q", "batch", "--hand", str(HAND), "--objects",
                          str(WORK / "two.txt"), "--out", str(folder), "--grasps", "2", "--steps",
                          "1500", "--validate", "--validate-seconds", "0.25", *flags],
                         capture_output=True, text=True)
    if run.returncode != 0:
        fail(f"the validated batch {flags} failed ({run.returncode}): {run.stdout}{run.stderr}")




def same_labels_and_figures(name, f, a, kept, how):
    """The grasp labels of dataset f (validated `how`) are those of a (every direction simulated),
    and so is each direction's figure where `kept`."""
    mine_labels, their_labels = f["grasps/qualities/held"][()], a["grasps/qualities/held"][()]
    if mine_labels.tolist() != their_labels.tolist():
        fail(f"{name}: labels {mine_labels} {how}, {their_labels} with all six simulated")
    for key in ("held", "slip", "turn", "seconds", "failed"):
        mine, theirs = f[f"grasps/validation/{key}"][()], a[f"grasps/validation/{key}"][()]
        if (mine[kept] != theirs[kept]).any():
            fail(f"{name}: validation/{key} {mine} {how} where all six simulated gave {theirs}")


validated = WORK / "validated"
every = WORK / "validated_all"
validated_batch(validated)
validated_batch(every, "--validate-all-directions")
axes = [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]]
stopped_early = 0
for name in ("object_0000_box", "object_0001_cylinder"):
    with h5py.File(validated / "grasps" / f"{name}.h5", "r") as f, \
            h5py.File(every / "grasps" / f"{name}.h5", "r") as a:
        tried = f["grasps/validation/held"][()] != -1
        same_labels_and_figures(name, f, a, tried, "stopping at the first let go")
        if (a["grasps/validation/held"][()] == -1).any():
            fail(f"{name}: --validate-all-directions left {a['grasps/validation/held'][()]}")
        for row, label in zip(f["grasps/validation/held"][()], f["grasps/qualities/held"][()]):
            if list(row).count(0) != (0 if label == 1 else 1):
                fail(f"{name}: directions {row} for the label {label}: not exactly one let go")
            stopped_early += list(row).count(-1) > 0
    with h5py.File(every / "grasps" / f"{name}.h5", "r") as f:
        held = f["grasps/qualities/held"][()]
        directions = f["grasps/validation/held"][()]
        slip = f["grasps/validation/slip"][()]
        turn = f["grasps/validation/turn"][()]
        seconds = f["grasps/validation/seconds"][()]
        failed = f["grasps/validation/failed"][()]
        if f["grasps/validation/directions"][()].tolist() != axes:
            fail(f"{name}: directions {f['grasps/validation/directions'][()]}")
        if directions.shape != (len(held), 6) or len(held) == 0:
            fail(f"{name}: validation of shape {directions.shape} for {len(held)} grasps")
        for i, label in enumerate(held):
            if int(label) != int(all(d == 1 for d in directions[i])):
                fail(f"{name} grasp {i}: held {label}, directions {directions[i]}")
            for k in range(6):
                within = slip[i][k] <= 5.0 and turn[i][k] <= 15.0 * 3.14159265358979 / 180.0
                if directions[i][k] not in (0, 1) or bool(directions[i][k]) != (within and not failed[i][k]):
                    fail(f"{name} grasp {i} direction {k}: held {directions[i][k]}, slip "
                         f"{slip[i][k]} mm, turn {turn[i][k]} rad, failed {failed[i][k]}")
                if not failed[i][k] and not 0 < seconds[i][k] <= 0.25 + 1e-9:
                    fail(f"{name} grasp {i} direction {k}: ran {seconds[i][k]} s of 0.25")
if not stopped_early:
    fail("no grasp left a direction untried: the stop at the first let go was not tried")

# --validate-statics: a direction statics holds ends after its 0.025 s probe (one step past it at
# most) with the object within 2 % of the let-go limits; every other direction is simulated as
# without it, so it gets the same figures; and the labels are the simulation's on these grasps.
# The manifest records the setting.
statics = WORK / "validated_statics"
validated_batch(statics, "--validate-all-directions", "--validate-statics")
by_statics = 0
for name in ("object_0000_box", "object_0001_cylinder"):
    with h5py.File(statics / "grasps" / f"{name}.h5", "r") as f, \
            h5py.File(every / "grasps" / f"{name}.h5", "r") as a:
        seconds = f["grasps/validation/seconds"][()]
        probed = (seconds < 0.025 + 0.0025 + 1e-9) & (seconds < a["grasps/validation/seconds"][()])
        by_statics += int(probed.sum())
        same_labels_and_figures(name, f, a, ~probed, "with statics")
        if (f["grasps/validation/held"][()][probed] != 1).any() or \
                (f["grasps/validation/slip"][()][probed] > 0.1 + 1e-12).any():
            fail(f"{name}: a probed direction let go or slipped over 0.1 mm: "
                 f"{f['grasps/validation/slip'][()]}")
if not by_statics:
    fail("statics held no direction of these grasps: --validate-statics was not tried")
if not json.loads((statics / "manifest.json").read_text())["settings"].get("validate_statics"):
    fail("the manifest does not record --validate-statics")
# A dataset is what validate, render, export, view and serve read as a plan's grasps: each grasp
# put back into a world from the file alone. In another process, validation of that world must
# give the batch's own figures for every direction (the dynamics amplify any difference in a
# pose or DOF), and each glTF scene must carry the file's epsilon and contact count.
name = "object_0001_cylinder"
run = subprocess.run([GRASPKIT, "-q", "validate", str(every / "grasps" / f"{name}.h5"), "--seconds",
                      "0.25", "--json"], capture_output=True, text=True)
if run.returncode != 0:
    fail(f"validate on a dataset failed ({run.returncode}): {run.stdout}{run.stderr}")
again = json.loads(run.stdout)["grasps"]
with h5py.File(every / "grasps" / f"{name}.h5", "r") as f:
    held, slip = f["grasps/validation/held"][()], f["grasps/validation/slip"][()]
    seconds, labels = f["grasps/validation/seconds"][()], f["grasps/qualities/held"][()]
if len(again) != len(labels):
    fail(f"validate saw {len(again)} grasps in a dataset of {len(labels)}")
for i, grasp in enumerate(again):
    if grasp["held"] != bool(labels[i]):
        fail(f"{name} grasp {i}: validated again {grasp['held']}, the dataset says {labels[i]}")
    for k, d in enumerate(grasp["directions"]):
        if d["held"] != bool(held[i][k]) or abs(d["slip_mm"] - slip[i][k]) > 1e-9 or \
                abs(d["seconds"] - seconds[i][k]) > 1e-9:
            fail(f"{name} grasp {i} direction {k}: validated again {d}, the dataset holds held "
                 f"{held[i][k]}, slip {slip[i][k]} mm, {seconds[i][k]} s")
glb = WORK / "dataset.glb"
run = subprocess.run([GRASPKIT, "-q", "export", str(single / "grasps" / f"{name}.h5"), "--gltf",
                      str(glb)], capture_output=True, text=True)
if run.returncode != 0:
    fail(f"export of a dataset failed ({run.returncode}): {run.stdout}{run.stderr}")
data = glb.read_bytes()
gltf = json.loads(data[20:20 + int.from_bytes(data[12:16], "little")])
with h5py.File(single / "grasps" / f"{name}.h5", "r") as f:
    epsilon = f["grasps/qualities/epsilon"][()]
    offsets = f["grasps/contacts/offsets"][()]
if len(gltf["scenes"]) != len(epsilon):
    fail(f"the glTF of a dataset of {len(epsilon)} grasps has {len(gltf['scenes'])} scenes")
for i, scene in enumerate(gltf["scenes"]):
    extras, count = scene["extras"], int(offsets[i + 1] - offsets[i])
    if extras["summary"]["epsilon"] != epsilon[i] or extras["summary"]["contacts"] != count or \
            len(extras["contacts"]) != count:
        fail(f"glTF scene {i}: {extras['summary']} with {len(extras['contacts'])} contacts; the "
             f"dataset holds epsilon {epsilon[i]} and {count} contacts")
# A grasp number past the dataset's end, and an object file changed since the batch, are refused
# with the file named, not drawn.
run = subprocess.run([GRASPKIT, "render", str(single / "grasps" / f"{name}.h5"), "--grasp", "4",
                      "--out", str(WORK / "none.png")], capture_output=True, text=True)
if run.returncode != 1 or "has 3 grasps" not in run.stderr:
    fail(f"--grasp 4 of 3 gave exit {run.returncode}: {run.stderr}")
changed = WORK / "changed"
shutil.copytree(objects, changed / "objects")
(changed / "one.txt").write_text(f"objects/{name}.xml\n")
batch(changed / "one.txt", changed / "out")
shutil.copy(objects / "object_0000_box.off", changed / "objects" / f"{name}.off")
run = subprocess.run([GRASPKIT, "render", str(changed / "out" / "grasps" / f"{name}.h5"), "--out",
                      str(WORK / "none.png")], capture_output=True, text=True)
if run.returncode != 1 or "changed since" not in run.stderr or f"{name}.h5" not in run.stderr:
    fail(f"a dataset whose object changed gave exit {run.returncode}: {run.stderr}")

# The load flags that change the hand are settings: a run with another closing direction does not
# resume into this one's folder, and the manifest records them.
run = batch(objects, single, "--close", "0=-", check=False)
if run.returncode != 1 or "other settings" not in run.stderr:
    fail(f"--close did not count as a setting: exit {run.returncode}: {run.stderr}")
closing = WORK / "closing"
batch(WORK / "two.txt", closing, "--close", "0=-")
if manifest(closing)["settings"].get("hand_options") != {"close": ["0=-"]}:
    fail(f"the manifest does not record --close: {manifest(closing)['settings']}")

# graspkit.load_dataset in Lua against h5py, on one file.
name = "object_0001_cylinder"
script = WORK / "read_dataset.lua"
script.write_text(f"""
local d = graspkit.load_dataset("{single / 'grasps' / (name + '.h5')}")
local out = {{name = d.object.name, mass = d.object.mass, hand = d.hand.name, seed = d.seed,
              epsilon = {{}}, closed = {{}}, x = {{}}, contacts = {{}}}}
for i, g in ipairs(d.grasps) do
  out.epsilon[i] = g.epsilon
  out.closed[i] = g.closed_dofs
  out.x[i] = g.pose.translation
  out.contacts[i] = #g.contacts
end
print(graspkit.json_encode(out))
""")
run = subprocess.run([GRASPKIT, "-q", "run", str(script), "--allow-read", str(single)],
                     capture_output=True, text=True)
if run.returncode != 0:
    fail(f"the Lua reader failed: {run.stdout}{run.stderr}")
lua = json.loads(run.stdout)
with h5py.File(single / "grasps" / f"{name}.h5", "r") as f:
    offsets = f["grasps/contacts/offsets"][()]
    expected = {
        "name": f["object/name"][()].decode(), "mass": float(f["object/mass"][()]),
        "hand": f["hand/name"][()].decode(), "seed": str(int(f.attrs["seed"])),
        "epsilon": [float(e) for e in f["grasps/qualities/epsilon"][()]],
        "closed": [[float(v) for v in row] for row in f["grasps/dofs/closed"][()]],
        "x": [[float(v) for v in t[:3, 3]] for t in f["grasps/transforms"][()]],
        "contacts": [int(offsets[i + 1] - offsets[i]) for i in range(len(offsets) - 1)],
    }
if lua != expected:
    fail(f"Lua read {lua}, h5py {expected}")
print("batch: every check passed")
