"""A small grasp dataset: for each of GraspIt!'s objects, plan Barrett grasps and store them.

    PYTHONPATH=build/bindings/python /usr/bin/python3 examples/python/grasp_dataset.py \
        ../shared/graspit-data --out dataset.npz [--steps 4000] [--objects 5]

One NumPy archive holds, for every grasp: the object's file (index into `objects`); the hand's
pre-grasp (4x4 pose in the object's frame and DOFs) and the closed hand (pose and DOFs); epsilon,
volume, the contact count, and the contact points and normals in the object's frame (padded with
NaN to the most contacts). The closed DOFs alone do not give the closed hand back when joints
broke away (the Barrett's fingertips): closing the hand from the pre-grasp (autograsp) does.
"""

import argparse
import pathlib

import numpy as np

import graspkit


def plan_object(hand_file, object_file, steps, top):
    world = graspkit.World()
    target = world.add_object(object_file)  # at the origin
    hand = world.add_robot(hand_file, graspkit.pose((0, 0, -400)))
    rows = []
    for planned in graspkit.plan(world, hand, target, steps=steps, top=top, threads=1):
        closed = planned.world()
        grasp = closed.robot().grasp(closed.body(target.name))
        to_object = np.linalg.inv(closed.body(target.name).pose)
        c = grasp.contacts
        rows.append({
            "pregrasp_pose": to_object @ planned.pregrasp_pose,
            "pregrasp_dofs": planned.pregrasp_dofs,
            "pose": to_object @ planned.pose,
            "dofs": planned.dofs,
            "epsilon": planned.epsilon,
            "volume": planned.volume,
            "points": (c.points @ to_object[:3, :3].T) + to_object[:3, 3],
            "normals": c.normals @ to_object[:3, :3].T,
        })
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("graspit_data", type=pathlib.Path, help="GraspIt!'s data folder")
    parser.add_argument("--out", type=pathlib.Path, required=True, help="the .npz to write")
    parser.add_argument("--steps", type=int, default=4000, help="search steps per object")
    parser.add_argument("--top", type=int, default=5, help="grasps kept per object")
    parser.add_argument("--objects", type=int, default=5, help="how many objects (by name)")
    args = parser.parse_args()

    hand_file = args.graspit_data / "models/robots/Barrett/Barrett.xml"
    objects = sorted((args.graspit_data / "models/objects").glob("*.xml"))[: args.objects]
    keys = ("pregrasp_pose", "pregrasp_dofs", "pose", "dofs", "epsilon", "volume", "points",
            "normals")
    table = {k: [] for k in ("object",) + keys}
    for index, object_file in enumerate(objects):
        rows = plan_object(hand_file, object_file, args.steps, args.top)
        print(f"{object_file.name}: {len(rows)} grasps, "
              f"{sum(r['epsilon'] > 0 for r in rows)} in force closure")
        for row in rows:
            table["object"].append(index)
            for key in keys:
                table[key].append(row[key])

    most = max((len(p) for p in table["points"]), default=0)
    pad = lambda a: np.vstack([a, np.full((most - len(a), 3), np.nan)])  # noqa: E731
    np.savez_compressed(
        args.out,
        objects=np.array([str(o) for o in objects]),
        hand=str(hand_file),
        object=np.array(table["object"], dtype=np.int32),
        pregrasp_pose=np.array(table["pregrasp_pose"]).reshape(-1, 4, 4),
        pregrasp_dofs=np.array(table["pregrasp_dofs"]).reshape(len(table["object"]), -1),
        pose=np.array(table["pose"]).reshape(-1, 4, 4),
        dofs=np.array(table["dofs"]).reshape(len(table["object"]), -1),
        epsilon=np.array(table["epsilon"]),
        volume=np.array(table["volume"]),
        contact_count=np.array([len(p) for p in table["points"]], dtype=np.int32),
        points=np.array([pad(p) for p in table["points"]]).reshape(-1, most, 3),
        normals=np.array([pad(n) for n in table["normals"]]).reshape(-1, most, 3),
    )
    print(f"wrote {len(table['object'])} grasps of {len(objects)} objects to {args.out}")


if __name__ == "__main__":
    main()
