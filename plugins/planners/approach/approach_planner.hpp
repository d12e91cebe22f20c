#pragma once
// The approach planner: brings the open hand straight in toward the object from evenly spread
// directions and ranks where it ends. Options (all optional):
//
//   directions   how many approach directions, Fibonacci-spread over a sphere around the
//                object's centre of mass in the object's frame (64)
//   rolls        how many roll angles about each direction, evenly spaced over a turn (4)
//
// A sample (direction i, roll k; step i * rolls + k) puts the hand's approach frame on the
// line from the sphere point through the object's centre of mass, pointing at it, and so far
// out that no part of the hand can reach the object's bounding sphere. The DOFs are open (each
// at the limit against its closing direction; a DOF that does not close keeps the world's
// value), as near as the request's posture space allows. The hand then moves in along its
// approach direction (approachToContact) until it touches anything, or its approach frame
// reaches the point where the line first meets the object. The state there is scored with the
// request's energy (use autograsp-quality to rank by the grasp closing there gives).
//
// Dropped samples: the line misses the object (a ring's hole), the hand collides where it
// starts (a table in the way), the end state is outside the search space's ranges, or the
// energy calls it illegal. The rest are ranked by energy (equal energies in sample order), up
// to the request's best-list size. Deterministic: samples are evaluated on request.threads
// threads and merged in sample order. Needs the complete or axis-angle position space.

#include <memory>

#include "graspkit/planning/planner.hpp"

namespace graspkit::approach {

std::unique_ptr<Planner> makeApproachPlanner(const PlanningRequest& request);

}  // namespace graspkit::approach
