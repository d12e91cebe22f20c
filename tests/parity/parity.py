"""The parity request through Python (tests/parity/parity_test.py runs it).

Usage: parity.py PLANNER_WORLD ROOT GRASP_WORLD STEPS SEED TOP SECONDS HAND OUT
Prints one JSON object: plan, grasp, validation, simulation, dataset (parity_test.py's schema).
"""

import json
import sys

import numpy as np

import graspkit


def pose7(matrix):
    t, q = graspkit.translation_quaternion(matrix)
    return [float(v) for v in t] + [float(v) for v in q]


def main():
    planner_world, root, grasp_world, steps, seed, top, seconds, hand_file, out = sys.argv[1:10]
    steps, seed, top, seconds = int(steps), int(seed), int(top), float(seconds)

    world = graspkit.load_world(planner_world, roots=[root])
    grasps = graspkit.plan(world, steps=steps, seed=seed, top=top)
    plan = [{"epsilon": g.epsilon, "volume": g.volume, "contacts": g.contact_count,
             "force_closure": g.force_closure, "pose": pose7(g.pose)} for g in grasps]

    closed = graspkit.load_world(planner_world, roots=[root])
    hand = closed.robot()
    hand.autograsp()
    measured = hand.grasp()
    grasp = {"epsilon": measured.epsilon, "volume": measured.volume,
             "contacts": len(measured.contacts), "force_closure": measured.force_closure}

    held = graspkit.validate(graspkit.load_world(grasp_world, roots=[root]), seconds=seconds)
    validation = {"held": held["held"], "directions_held": held["directions_held"],
                  "settle_seconds": held["settle_seconds"],
                  "slip": [d["slip_mm"] for d in held["directions"]]}

    moving = graspkit.load_world(grasp_world, roots=[root])
    run = moving.simulate(seconds=seconds, autograsp=True)
    simulation = {"completed": run["completed"], "steps": run["steps"], "time": run["time"],
                  "bodies": [pose7(b.pose) for b in moving.bodies],
                  "dofs": [float(v) for v in np.concatenate([r.dofs for r in moving.robots])]}
    # One generated object's dataset: planned, saved, read back.
    made = graspkit.generate_object(out, 0, seed=2)
    data = graspkit.plan_dataset(hand_file, made["file"], grasps=3, steps=1500, seed=5)
    data.save(f"{out}/dataset.h5")
    dataset = [{"epsilon": g.epsilon, "volume": g.volume, "force_closure": g.force_closure,
                "pose": pose7(g.pose)} for g in graspkit.load_dataset(f"{out}/dataset.h5").grasps]
    json.dump({"plan": plan, "grasp": grasp, "validation": validation,
               "simulation": simulation, "dataset": dataset}, sys.stdout)


if __name__ == "__main__":
    main()
