// A C++ host: load a world, close its first hand on its first graspable body, print the grasp as
// `graspkit grasp WORLD --autograsp` prints it (the same lines, so the two can be compared).
//   grasp_report WORLD [ROOT]
// ROOT is where the world's <filename>s are looked up (graspkit's --root).

#include <cstdio>
#include <optional>

#include "graspkit/base/error.hpp"
#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/grasp/grasp.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/world.hpp"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: grasp_report WORLD [ROOT]\n");
    return 2;
  }
  try {
    graspkit::LoadOptions options;
    if (argc > 2) options.roots.push_back(argv[2]);
    graspkit::World world = graspkit::loadWorldFile(argv[1], options);
    const std::optional<int> hand = world.firstHand();
    if (!hand) throw graspkit::Error("the world has no hand");
    std::optional<int> object;
    for (int i = 0; i < static_cast<int>(world.bodies().size()) && !object; ++i)
      if (world.bodies()[i].isDynamic()) object = i;
    if (!object) throw graspkit::Error("the world has no graspable body");

    graspkit::autoGrasp(world, *hand);
    const graspkit::Grasp grasp =
        graspkit::analyzeGrasp(world, *hand, graspkit::BodyRef::body(*object));
    std::printf("%zu contacts with the object\n", grasp.contacts.size());
    std::printf("epsilon %.7g\nvolume %.7g\nforce closure %s\n", grasp.epsilon, grasp.volume,
                grasp.forceClosure ? "yes" : "no");
    return 0;
  } catch (const graspkit::Error& e) {
    std::fprintf(stderr, "grasp_report: %s\n", e.what());
    return 1;
  }
}
