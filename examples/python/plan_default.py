"""The README's main job from Python: plan grasps on models/worlds/default.xml, print the best.

    PYTHONPATH=build/bindings/python /usr/bin/python3 examples/python/plan_default.py [--top N]

Run from the project folder (the world's model paths are looked up below models/).
"""

import argparse
import pathlib

import graspkit

MODELS = pathlib.Path(__file__).resolve().parents[2] / "models"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--top", type=int, default=10, help="how many grasps to print")
    parser.add_argument("--steps", type=int, default=40000, help="search steps")
    args = parser.parse_args()

    world = graspkit.load_world(MODELS / "worlds/default.xml", roots=[MODELS])
    hand = world.robot()
    grasps = graspkit.plan(world, hand, steps=args.steps, top=args.top)
    target = next(b for b in world.bodies if b.is_dynamic)  # what plan() grasps by default
    print(f"{hand.name} grasping {target.name}: {len(grasps)} grasps")
    print("rank  epsilon   volume     contacts  force-closure")
    for rank, grasp in enumerate(grasps, 1):
        print(f"{rank:4}  {grasp.epsilon:8.5f}  {grasp.volume:9.6f}  {grasp.contact_count:8}  "
              f"{'yes' if grasp.force_closure else 'no'}")


if __name__ == "__main__":
    main()
