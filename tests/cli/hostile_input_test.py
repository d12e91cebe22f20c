#!/usr/bin/env python3
"""Issue 36's reproducers, run against the program as an attacker or a careless user would.

Usage: hostile_input_test.py GRASPKIT SOURCE_DIR WORK_DIR PLUGIN_CORPUS_DIR

Each case builds its hostile input, runs one command and checks what must hold: a clean error
(exit 1 or 2, never 3 or a signal) whose message says why, or the right result, and nothing
outside the output folder touched. ctest runs it in the plain build and in the ASan/UBSan build,
so every case also runs under the sanitizers.
"""

import json
import os
import shutil
import stat
import subprocess
import sys
import time
from pathlib import Path

GRASPKIT, SOURCE, WORK, CORPUS = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3]), Path(sys.argv[4])
MODELS = SOURCE / "models"
HAND = MODELS / "robots/parallel_jaw/parallel_jaw.xml"
failures = []


def run(*args, env=None, stdout=subprocess.PIPE, timeout=60):
    full_env = dict(os.environ, **(env or {}))
    started = time.monotonic()
    result = subprocess.run([GRASPKIT, *map(str, args)], stdout=stdout, stderr=subprocess.PIPE,
                            env=full_env, timeout=timeout)
    result.seconds = time.monotonic() - started
    result.out = result.stdout.decode("utf-8", "replace") if result.stdout else ""
    result.err = result.stderr.decode("utf-8", "replace")
    return result


def check(name, condition, detail=""):
    print(("ok   " if condition else "FAIL ") + name + ("" if condition else ": " + detail))
    if not condition:
        failures.append(name)


def refused(name, result, codes, *words):
    """A clean refusal: one of `codes` (never 3, never a signal) and each word in the message."""
    text = result.err + result.out
    check(name, result.returncode in codes and all(w in text for w in words),
          f"exit {result.returncode}, expected {codes} with {words}: {text[-600:]}")


def case_folder(name):
    folder = WORK / name
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir(parents=True)
    return folder


def box_world(folder, second_box_at):
    world = folder / "world.xml"
    world.write_text(f"""<?xml version="1.0"?>
<world>
  <obstacle><filename>obstacles/floor.xml</filename></obstacle>
  <graspableBody><filename>objects/box.xml</filename>
    <transform><fullTransform>(+1 0 0 0)[0 0 60.1]</fullTransform></transform></graspableBody>
  <graspableBody><filename>objects/box.xml</filename>
    <transform><fullTransform>(+1 0 0 0)[{second_box_at}]</fullTransform></transform></graspableBody>
</world>
""")
    return world


# Item 2: a robot named like a path stays inside --out.
def convert_names_stay_inside_out():
    folder = case_folder("convert_names")
    victim = folder / "victim"
    victim.mkdir()
    (victim / "important.urdf").write_text("keep me")
    urdf = folder / "evil.urdf"
    text = (MODELS / "robots/urdf_gripper/urdf_gripper.urdf").read_text()
    start = text.index('<robot name="') + len('<robot name="')
    end = text.index('"', start)
    urdf.write_text(text[:start] + f"{victim}/important" + text[end:])
    out = folder / "out"
    result = run("convert", urdf, "--to", "urdf", "--out", out)
    check("convert: a robot named like an absolute path writes inside --out",
          (victim / "important.urdf").read_text() == "keep me" and result.returncode in (0, 1),
          f"exit {result.returncode}: {result.err}")


# Item 3: output never replaces anything but a regular file.
def fifo_output_is_refused():
    folder = case_folder("fifo_out")
    fifo = folder / "picture.png"
    os.mkfifo(fifo)
    result = run("render", MODELS / "worlds/drop.xml", "--root", MODELS, "--out", fifo,
                 "--size", "16x16")
    refused("render --out FIFO is refused", result, (1,), "not a regular file")
    check("render --out FIFO leaves the FIFO", stat.S_ISFIFO(os.lstat(fifo).st_mode))


# Item 5: a body Siconos would abort on.
def tiny_mass_is_refused():
    folder = case_folder("tiny_mass")
    shutil.copy(MODELS / "objects/box.iv", folder / "box.iv")
    body = (MODELS / "objects/box.xml").read_text().replace("<mass>300</mass>", "<mass>1e-300</mass>")
    (folder / "box.xml").write_text(body)
    world = folder / "world.xml"
    world.write_text(f"""<?xml version="1.0"?>
<world><graspableBody><filename>{folder / 'box.xml'}</filename></graspableBody></world>
""")
    refused("simulate: a 1e-300 g body is refused, not an abort", run("simulate", world, "--seconds", "0.01"),
            (1,), "mass")


# Item 9: two boxes sharing volume with no faces crossing (the same footprint) and the same
# object twice at one pose.
def overlapping_boxes_are_refused():
    for name, at in [("overlap_footprint", "0 0 110.1"), ("overlap_same_pose", "0 0 60.1")]:
        world = box_world(case_folder(name), at)
        refused(f"simulate: {name} interpenetrates", run("simulate", world, "--root", MODELS,
                                                         "--seconds", "0.05"), (1,), "interpenetrate")
    # A time step so small that the simulation would never end.
    world = box_world(case_folder("tiny_dt"), "0 0 180.2")
    refused("simulate --dt 1e-300", run("simulate", world, "--root", MODELS, "--dt", "1e-300",
                                        timeout=30), (1,), "time step")
    # The box resting on the floor and another standing on it: a legal start, simulated.
    world = box_world(case_folder("stacked"), "0 0 180.2")
    result = run("simulate", world, "--root", MODELS, "--seconds", "0.05")
    check("simulate: a box standing on another runs", result.returncode == 0, result.err)


# Item 10: exit 3 on bad input.
def batch_list_not_utf8():
    folder = case_folder("batch_utf8")
    (folder / "list.txt").write_bytes(b"box\xff\xfe.xml\n")
    refused("batch: a list line that is not UTF-8", run("batch", "--hand", HAND, "--objects",
                                                        folder / "list.txt", "--out", folder / "out"),
            (1,), "list.txt:1", "not UTF-8")


def symlink_loop_robot():
    folder = case_folder("symlink_loop")
    os.symlink("loop2.xml", folder / "loop1.xml")
    os.symlink("loop1.xml", folder / "loop2.xml")
    world = folder / "world.xml"
    world.write_text(f"""<?xml version="1.0"?>
<world><robot><filename>{folder / 'loop1.xml'}</filename></robot></world>
""")
    refused("info: a robot file that is a loop of symbolic links", run("info", world), (1,),
            "world.xml", "symbolic links")


# Item 11: plugins that print while loading, or crash when loaded a second time.
def unruly_plugins():
    folder = case_folder("plugins")
    marker = folder / "marker"
    env = {"GRASPKIT_PLUGIN_PATH": str(CORPUS / "unruly"), "GRASPKIT_TEST_MARKER": str(marker)}
    result = run("plugins", "--json", env=env)
    try:
        listed = {Path(p["file"]).name: p for p in json.loads(result.out)["plugins"]}
    except (ValueError, KeyError) as e:
        check("plugins --json stays JSON with a plugin printing to stdout", False,
              f"{e}: {result.out[:300]}")
        return
    check("plugins --json stays JSON with a plugin printing to stdout", result.returncode == 0,
          result.err)
    check("plugins: a plugin crashing on its second load is listed, not loaded again",
          listed.get("second_load_crashes.so", {}).get("loaded") is True and marker.exists(),
          json.dumps(listed))


# Item 13: runaways.
def huge_extrusion():
    folder = case_folder("extrusion")
    n = 2000
    spine = " ".join(f"0 {i * 0.01:.2f} 0" for i in range(n))
    cross = " ".join(f"{(i % 7) * 0.1:.1f} {(i % 5) * 0.1:.1f}" for i in range(n))
    (folder / "ext.wrl").write_text(
        f"#VRML V2.0 utf8\nShape {{ geometry Extrusion {{ spine [ {spine} ] crossSection [ {cross} ] }} }}\n")
    (folder / "ext.xml").write_text('<?xml version="1.0"?><root><geometryFile type="Inventor">ext.wrl'
                                    "</geometryFile><material>wood</material><mass>100</mass></root>\n")
    result = run("info", folder / "ext.xml", timeout=120)
    refused("info: a 2000 x 2000 extrusion is refused", result, (1,), "quadrilaterals")
    check("info: the extrusion is refused quickly", result.seconds < 10, f"{result.seconds:.1f} s")


def closed_stdout():
    result = run("info", MODELS / "worlds/drop.xml", "--root", MODELS, "--json",
                 stdout=subprocess.DEVNULL)
    check("info --json to /dev/null succeeds", result.returncode == 0, result.err)
    with open(os.devnull, "rb") as closed:  # a read-only descriptor: every write fails
        result = subprocess.run([GRASPKIT, "info", str(MODELS / "worlds/drop.xml"), "--root",
                                 str(MODELS), "--json"], stdout=closed, stderr=subprocess.PIPE)
    check("info --json to an unwritable stdout fails", result.returncode == 1,
          f"exit {result.returncode}")


# Item 14: the lower ones.
def numeric_flags():
    plan = ["plan", MODELS / "worlds/gripper_box.xml", "--root", MODELS, "--steps", "10"]
    refused("plan --seed -1", run(*plan, "--seed", "-1"), (2,), "seed")
    refused("plan --seed 2^64", run(*plan, "--seed", "18446744073709551616"), (2,), "seed")
    refused("plan --top -3", run(*plan, "--top", "-3"), (2,), "--top")
    refused("plan --seconds nan", run("plan", MODELS / "worlds/gripper_box.xml", "--seconds", "nan"),
            (2,), "finite")
    batch = ["batch", "--hand", HAND, "--objects", MODELS / "objects", "--out", WORK / "unused"]
    refused("batch --shard 1/99999999999", run(*batch, "--shard", "1/99999999999"), (1, 2), "--shard")
    refused("batch --object-timeout nan", run(*batch, "--object-timeout", "nan"), (2,), "finite")
    refused("validate --grasp 0", run("validate", MODELS / "worlds/gripper_box.xml", "--grasp", "0"),
            (2,), "--grasp")


def stale_objects_staging():
    folder = case_folder("objects_staging")
    stale = folder / ".objects-staging-999999999-deadbeef"  # no process has this id
    stale.mkdir()
    (stale / "left.off").write_text("OFF\n")
    result = run("objects", "--generate", "2", "--out", folder)
    check("objects: a killed run's staging folder is removed", result.returncode == 0 and
          not stale.exists(), f"exit {result.returncode}: {result.err}")


def sandboxed_existence():
    folder = case_folder("sandbox")
    script = folder / "probe.lua"
    script.write_text("""
local function try(file)
  local f = io.open(graspkit.script_folder .. "/b.xml", "w")
  f:write('<?xml version="1.0"?><root><geometryFile type="Inventor">' .. file ..
          '</geometryFile><material>wood</material><mass>100</mass></root>')
  f:close()
  local ok, err = pcall(function() graspkit.new_world():add_object(graspkit.script_folder .. "/b.xml") end)
  print((tostring(err):gsub(file, "FILE", 1, true)))
end
try("/etc/passwd")
try("/etc/no_such_file_here")
""")
    result = run("run", script)
    lines = [l for l in result.out.splitlines() if l.strip()]
    check("sandbox: a mesh outside gives the same refusal whether it exists or not",
          len(lines) == 2 and lines[0] == lines[1] and "sandbox" in lines[0], "\n".join(lines))
    os.symlink("/etc/passwd", folder / "link.iv")
    script.write_text("""
local f = io.open(graspkit.script_folder .. "/b.xml", "w")
f:write('<?xml version="1.0"?><root><geometryFile type="Inventor">link.iv</geometryFile>' ..
        '<material>wood</material><mass>100</mass></root>')
f:close()
print(select(2, pcall(function() graspkit.new_world():add_object(graspkit.script_folder .. "/b.xml") end)))
""")
    result = run("run", script)
    check("sandbox: a refusal does not name a symbolic link's target",
          "sandbox" in result.out and "/etc/passwd" not in result.out, result.out)


def escape_codes():
    folder = case_folder("escapes")
    urdf = folder / "evil.urdf"
    urdf.write_bytes(b'<?xml version="1.0"?>\n<robot name="evil\x1b]0;pwned\x07\xc2\x9b31m">\n'
                     b'<link name="base"><collision><geometry><box size="0.1 0.1 0.1"/></geometry>'
                     b'</collision></link><link name="f\x1b[2J"><collision><geometry>'
                     b'<box size="0.01 0.01 0.05"/></geometry></collision></link>\n'
                     b'<joint name="j" type="revolute"><parent link="base"/><child link="f\x1b[2J"/>'
                     b'<axis xyz="0 1 0"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>\n'
                     b'</robot>\n')
    result = run("info", urdf)
    raw = result.stdout + result.stderr
    check("info: escape codes in names are shown, not sent", result.returncode == 0 and
          b"\x1b" not in raw and b"\x07" not in raw and b"\xc2\x9b" not in raw and
          b"\\x1b]0;pwned" in raw, repr(raw[:400]))
    result = run("info", urdf, "--json")
    check("info --json: escape codes in names are JSON escapes",
          result.returncode == 0 and "\\u001b]0;pwned" in result.out and
          json.loads(result.out)["robots"][0]["name"].startswith("evil\x1b"), result.out[:300])
    # A model file whose name is not UTF-8 would name a body that no saved world could hold.
    shutil.copy(MODELS / "objects/box.xml", folder / "box.xml")
    shutil.copy(MODELS / "objects/box.iv", folder / "box.iv")
    latin_name = os.fsencode(folder) + b"/caf\xe9.xml"
    shutil.copy(folder / "box.xml", latin_name)
    refused("info: a model file whose path is not UTF-8", run("info", os.fsdecode(latin_name)), (1,),
            "not UTF-8")
    saved = os.fsencode(folder) + b"/w\xe9.xml"
    refused("info: a world saved to a path that is not UTF-8", run(
        "simulate", MODELS / "worlds/drop.xml", "--root", MODELS, "--seconds", "0.01", "--out",
        os.fsdecode(saved)), (1,), "not UTF-8")
    bad = folder / "latin1.urdf"
    bad.write_bytes(b'<?xml version="1.0"?>\n<robot name="caf\xe9">\n</robot>\n')
    refused("info: an XML file that is not UTF-8", run("info", bad), (1,), "latin1.urdf:2",
            "not UTF-8")


# Item 4: datasets that once made libhdf5 read past its buffers or ask for exabytes (the dataset
# fuzz target's finds), loaded by a sandboxed script: an error naming the file, never a crash.
def hostile_datasets():
    folder = case_folder("datasets")
    inputs = sorted((SOURCE / "fuzz/regressions/dataset_fuzz").glob("crash-*"))
    check("datasets: the fuzz target's finds are there to replay", len(inputs) >= 2, str(inputs))
    for k, found in enumerate(inputs):
        shutil.copy(found, folder / f"d{k}.h5")
    script = folder / "load.lua"
    script.write_text(f"""
for k = 0, {len(inputs) - 1} do
  local ok, err = pcall(graspkit.load_dataset, graspkit.script_folder .. "/d" .. k .. ".h5")
  print(ok, err)
end
""")
    result = run("run", script)
    lines = [l for l in result.out.splitlines() if l.strip()]
    check("datasets: each hostile dataset is an error naming it", result.returncode == 0 and
          len(lines) == len(inputs) and all(l.startswith("false") and ".h5" in l for l in lines),
          result.out + result.err[-400:])


WORK.mkdir(parents=True, exist_ok=True)
for case in [convert_names_stay_inside_out, fifo_output_is_refused, tiny_mass_is_refused,
             overlapping_boxes_are_refused, batch_list_not_utf8, symlink_loop_robot, unruly_plugins,
             huge_extrusion, closed_stdout, numeric_flags, stale_objects_staging,
             sandboxed_existence, escape_codes, hostile_datasets]:
    case()
if failures:
    print(f"{len(failures)} hostile-input case(s) failed")
    sys.exit(1)
print("every hostile-input case held")
