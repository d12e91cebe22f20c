#!/usr/bin/env python3
"""graspkit serve against hostile and careless requests, on the project's default world.

Usage: serve_requests_test.py GRASPKIT SOURCE_DIR WORK_DIR

A robot file alone opens as a bare hand: it closes, and plan and validate say there is no object.

Every request without the token, or naming another host, is refused (403); malformed bodies,
bad numbers and indices get 400 with a message; files outside the allowed folders are refused
(403) and not written, symbolic links included, and so is a file outside them that a loaded world
names; an oversized body gets 413; none of it changes
the world, and the server still answers and stops on SIGTERM. The one allowed save loads back
with `graspkit grasp` to the DOFs the server shows. ctest runs it under the sanitizers too.
"""

import http.client
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
WORLD = SOURCE / "models/worlds/default.xml"
failures = []


def check(name, condition, detail=""):
    print(("ok   " if condition else "FAIL ") + name + ("" if condition else ": " + str(detail)))
    if not condition:
        failures.append(name)


def start():
    server = subprocess.Popen([GRASPKIT, "-q", "serve", str(WORLD), "--port", "0",
                               "--allow-write", str(WORK / "out")],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    line = server.stdout.readline()
    match = re.search(r"127\.0\.0\.1:(\d+)/\?token=([0-9a-f]{32})", line)
    if not match:
        server.kill()
        sys.exit(f"graspkit serve printed no address: {line!r} {server.stderr.read()}")
    return server, int(match.group(1)), match.group(2)


def request(port, method, path, body=None, headers=None):
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=120)
    connection.request(method, path, body=body, headers=headers or {})
    response = connection.getresponse()
    data = response.read()
    connection.close()
    return response.status, data


def main():
    shutil.rmtree(WORK, ignore_errors=True)
    (WORK / "out").mkdir(parents=True)
    (WORK / "elsewhere").mkdir()
    server, port, token = start()
    auth = {"X-Graspkit-Token": token}

    def act(action, args=None, raw=None):
        body = raw if raw is not None else json.dumps(args if args is not None else {})
        status, data = request(port, "POST", f"/api/{action}", body, auth)
        try:
            answer = json.loads(data)
        except ValueError:
            answer = {"error": data[:80]}
        return status, answer

    try:
        # The token, and the Host header.
        check("page without the token", request(port, "GET", "/")[0] == 403)
        check("state without the token", request(port, "POST", "/api/state", "{}")[0] == 403)
        check("a wrong token", request(port, "POST", "/api/state", "{}",
                                       {"X-Graspkit-Token": "0" * 32})[0] == 403)
        check("the token in the address",
              request(port, "GET", f"/?token={token}")[0] == 200)
        check("another host name", request(port, "POST", "/api/state", "{}",
                                           {**auth, "Host": "evil.example:80"})[0] == 403)
        status, first = act("state")
        check("state with the token", status == 200 and "hand" in first, first)

        # Malformed requests: 400 and a message, nothing changed.
        bad = [
            ("not JSON", "pose", None, "{translation"),
            ("a list, not an object", "pose", None, "[1, 2]"),
            ("a short translation", "pose", {"translation": [1, 2], "quaternion": [1, 0, 0, 0]}, None),
            ("a huge translation", "pose", {"translation": [1e300, 0, 0], "quaternion": [1, 0, 0, 0]}, None),
            ("a text number", "pose", {"translation": ["NaN", 0, 0], "quaternion": [1, 0, 0, 0]}, None),
            ("a zero quaternion", "pose", {"translation": [0, 0, 0], "quaternion": [0, 0, 0, 0]}, None),
            ("too few DOFs", "dofs", {"values": [0.1]}, None),
            ("a DOF that is text", "dofs", {"values": ["a"] * len(first["hand"]["dofs"])}, None),
            ("a group that is a number", "dofs", {"values": [0] * len(first["hand"]["dofs"]), "group": 3}, None),
            ("eigengrasps of the wrong count", "eigengrasps", {"amplitudes": [0] * 40}, None),
            ("a grasp index with no grasps", "show_grasp", {"index": 0}, None),
            ("a fractional grasp index", "show_grasp", {"index": 0.5}, None),
            ("an unknown energy", "plan", {"seconds": 1, "energy": "nonsense"}, None),
            ("a negative plan time", "plan", {"seconds": -1}, None),
            ("a script language", "script", {"language": "perl"}, None),
            ("a picture of 1e9 pixels", "picture", {"file": str(WORK / "out/p.png"), "width": 100000}, None),
        ]
        for name, action, args, raw in bad:
            status, answer = act(action, args, raw)
            check(f"{name}: 400 with a message", status == 400 and answer.get("error"), (status, answer))
        status, answer = act("frobnicate")
        check("an unknown action: 404 naming the actions", status == 404 and "autograsp" in answer.get("error", ""),
              (status, answer))
        status, answer = act("undo")
        check("nothing to undo: 409", status == 409, (status, answer))
        status, _ = request(port, "POST", "/api/state", "x" * (2 << 20), auth)
        check("a 2 MiB body: 413", status == 413, status)

        # Files: only below --allow-write, symbolic links followed before the check.
        outside = WORK / "elsewhere/world.xml"
        link = WORK / "out/link.xml"
        link.symlink_to(outside)
        for name, file in [("a file outside", outside), ("../ out of the folder", WORK / "out/../elsewhere/w2.xml"),
                           ("a link out of the folder", link)]:
            status, answer = act("save", {"file": str(file)})
            check(f"save {name}: 403", status == 403, (status, answer))
        check("nothing was written outside", not any((WORK / "elsewhere").iterdir()))
        status, answer = act("picture", {"file": str(WORK / "elsewhere/p.png")})
        check("a picture outside: 403", status == 403, (status, answer))
        status, answer = act("load", {"file": "/etc/passwd"})
        check("load /etc/passwd: 403", status == 403, (status, answer))
        # A world inside the folders that names a body outside them: the body is a read too.
        shutil.copy(SOURCE / "models/objects/box.xml", WORK / "elsewhere/box.xml")
        shutil.copy(SOURCE / "models/objects/box.iv", WORK / "elsewhere/box.iv")
        (WORK / "out/names_outside.xml").write_text(
            "<?xml version='1.0' ?>\n<world>\n  <graspableBody>\n"
            f"    <filename>{WORK / 'elsewhere/box.xml'}</filename>\n"
            "    <transform><fullTransform>(+1 +0 +0 +0)[+0 +0 +0]</fullTransform></transform>\n"
            "  </graspableBody>\n  <robot>\n"
            f"    <filename>{SOURCE / 'models/robots/bh8/bh8.xml'}</filename>\n"
            "    <transform><fullTransform>(+1 +0 +0 +0)[+0 +0 +200]</fullTransform></transform>\n"
            "  </robot>\n</world>\n")
        status, answer = act("load", {"file": str(WORK / "out/names_outside.xml")})
        check("load a world naming a body outside: 403 naming it",
              status == 403 and "elsewhere/box.xml" in answer.get("error", ""), (status, answer))
        status, answer = act("load", {"file": str(WORK / "out/missing.xml")})
        check("load a missing file: 400 naming it", status == 400 and "missing.xml" in answer.get("error", ""),
              (status, answer))

        status, now = act("state")
        check("the refused requests changed nothing",
              now["hand"] == first["hand"] and now["undo"] == first["undo"], now["hand"])

        # One real change, saved and loaded back by the CLI.
        values = [d["min"] + 0.3 * (d["max"] - d["min"]) for d in first["hand"]["dofs"]]
        status, moved = act("dofs", {"values": values})
        check("dofs: 200", status == 200, moved)
        saved = WORK / "out/saved.xml"
        status, answer = act("save", {"file": str(saved)})
        check("save inside the folder: 200", status == 200 and saved.exists(), (status, answer))
        if saved.exists():
            back = json.loads(subprocess.run([GRASPKIT, "-q", "grasp", str(saved), "--json"], capture_output=True,
                                             text=True, check=True).stdout)
            shown = [d["value"] for d in moved["hand"]["dofs"]]
            check("the saved world loads back to the same DOFs",
                  all(abs(a - b) < 1e-9 for a, b in zip(back["dof_values"], shown)), (back["dof_values"], shown))
        status, answer = act("picture", {"file": str(WORK / "out/p.png"), "width": 64, "height": 48})
        check("a picture inside: a PNG", status == 200 and (WORK / "out/p.png").read_bytes()[:4] == b"\x89PNG",
              (status, answer))
        status, _ = act("state")
        check("the server still answers", status == 200)
    finally:
        server.send_signal(signal.SIGTERM)
        try:
            code = server.wait(timeout=20)
        except subprocess.TimeoutExpired:
            server.kill()
            code = "hung"
    check("SIGTERM stops the server with status 0", code == 0, code)

    # A bare hand (a robot file, no object): shaped and closed; nothing to plan or validate.
    global WORLD
    WORLD = SOURCE / "models/robots/parallel_jaw/parallel_jaw.xml"
    server, port, token = start()
    auth = {"X-Graspkit-Token": token}
    try:
        status, data = request(port, "POST", "/api/autograsp", "{}", auth)
        answer = json.loads(data)
        check("a bare hand closes", status == 200 and answer["object"] is None and
              answer["quality"]["epsilon"] is None and answer["ended"], (status, answer))
        for action in ("plan", "validate"):
            status, data = request(port, "POST", f"/api/{action}", "{}", auth)
            check(f"{action} without an object: 409", status == 409, (status, data))
    finally:
        server.send_signal(signal.SIGTERM)
        server.wait(timeout=20)
    if failures:
        sys.exit(f"{len(failures)} failed: {', '.join(failures)}")


main()
