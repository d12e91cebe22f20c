#pragma once
// A search energy: what a grasp planner minimises over hand states. GraspIt!'s energies are
// built in under these names (the registry also accepts GraspIt!'s factory names, e.g.
// CONTACT_ENERGY):
//
//   contact                   mean over virtual contacts of |d| + 50 (1 - n.d/|d|), d from the
//                             contact to the nearest object point, n the contact's normal
//   potential-quality         -epsilon of a force-only wrench space of the virtual contacts,
//                             each scaled by how near it is; +1 with fewer than 3 near contacts.
//                             Epsilon of the exact hull by HullMethod::NearestFacet, not of
//                             GraspIt!'s merged qhull hull (they differ only on near-degenerate
//                             wrench sets, and nothing compares this energy with GraspIt!'s)
//   guided-potential-quality  potential quality where it is <= 0, contact energy elsewhere
//   autograsp-quality         close the hand, then -(30 volume + 100 max(epsilon, 0)); a
//                             close that cannot touch the object (close_reach.hpp) is not
//                             run: its grasp has no contact, so the energy is -0
//   strict-autograsp          approach up to 30 mm keeping the pose only if the palm touches,
//                             then autograsp quality; 0 becomes 1e8
//
// A plugin adds its own with Registrar::addSearchEnergy. An energy object belongs to one
// search thread; the registry makes one per thread.

#include <functional>
#include <memory>
#include <string>
#include <string_view>

namespace graspkit {

class PlanningScene;

class SearchEnergy {
 public:
  virtual ~SearchEnergy() = default;
  // The energy of the scene as it stands (the hand placed, not colliding when
  // rejectsCollisions()). It may move the hand: the caller puts it back.
  virtual double evaluate(PlanningScene& scene) = 0;
  // The energy as evaluate() gives it, or, once it is certain to exceed `bound`, some value
  // above `bound`: a search that will reject any energy above the bound need not finish the
  // sum. The default evaluates in full.
  virtual double evaluateBelow(PlanningScene& scene, double bound) {
    (void)bound;
    return evaluate(scene);
  }
  // Whether a colliding hand makes a state illegal (GraspIt!'s compliant and dynamic energies
  // do their own checks).
  virtual bool rejectsCollisions() const { return true; }
  // Whether one evaluation costs more than a collision check (it closes the hand, or calls
  // user code). A search checks collisions first for these; for cheap energies it may evaluate
  // first and check collisions only for states it would move to.
  virtual bool expensive() const { return true; }
};

using SearchEnergyFactory = std::function<std::unique_ptr<SearchEnergy>()>;

// Our name for one of GraspIt!'s energy factory names ("CONTACT_ENERGY" -> "contact"), or the
// name unchanged.
std::string canonicalEnergyName(std::string_view name);

// How a built-in energy computes the epsilon it uses (epsilonMethodName() in
// grasp/wrench_space.hpp): "nearest facet (exact)" for the potential-quality energies, GraspIt!'s
// qhull for the autograsp ones; empty for the contact energy and any other name.
std::string_view energyEpsilonMethod(std::string_view name);

// GraspIt!'s energies under graspkit's names (contact, potential-quality, ...), with their
// factories: the Registry (plugin/registry.hpp) starts with them, and plugins add more there.
std::vector<std::pair<std::string, SearchEnergyFactory>> builtinSearchEnergies();

}  // namespace graspkit
