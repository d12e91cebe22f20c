/* A C host: load a world, close its first hand on its first graspable body, print the grasp as
 * `graspkit grasp WORLD --autograsp` prints it (the same lines, so the two can be compared).
 *   grasp_report WORLD [ROOT]
 * ROOT is where the world's <filename>s are looked up (graspkit's --root). */
#include <stdio.h>

#include "graspkit.h"

/* Prints the failure and gives the status back, so that each call reads as one line below. */
static int check(graspkit_status status, const char* what) {
  if (status != GRASPKIT_OK)
    fprintf(stderr, "grasp_report: %s: %s: %s\n", what, graspkit_status_name(status),
            graspkit_last_error());
  return status != GRASPKIT_OK;
}

int main(int argc, char** argv) {
  graspkit_world* world = NULL;
  graspkit_grasp* grasp = NULL;
  graspkit_load_options options = {NULL, 0, 0};
  const char* roots[1];
  int32_t hand = 0, object = -1, bodies = 0, i;
  int graspable = 0, failed = 1;
  size_t contacts = 0;
  graspkit_quality quality;

  if (argc < 2) {
    fprintf(stderr, "usage: grasp_report WORLD [ROOT]\n");
    return 2;
  }
  if (graspkit_abi_version() != GRASPKIT_ABI_VERSION) {
    fprintf(stderr, "grasp_report: built for ABI %d, the library is %u\n", GRASPKIT_ABI_VERSION,
            (unsigned)graspkit_abi_version());
    return 1;
  }
  if (argc > 2) {
    roots[0] = argv[2];
    options.roots = roots;
    options.root_count = 1;
  }
  if (check(graspkit_world_load(argv[1], &options, &world), "load")) goto done;
  if (check(graspkit_world_first_hand(world, &hand), "hand")) goto done;
  if (check(graspkit_world_body_count(world, &bodies), "bodies")) goto done;
  for (i = 0; i < bodies && object < 0; ++i) {
    if (check(graspkit_body_is_graspable(world, i, &graspable), "body")) goto done;
    if (graspable) object = i;
  }
  if (object < 0) {
    fprintf(stderr, "grasp_report: the world has no graspable body\n");
    goto done;
  }
  if (check(graspkit_robot_autograsp(world, hand, NULL), "autograsp")) goto done;
  if (check(graspkit_grasp_analyze(world, hand, object, GRASPKIT_GWS_L1, &grasp), "analyze"))
    goto done;
  if (check(graspkit_grasp_contact_count(grasp, &contacts), "contacts")) goto done;
  if (check(graspkit_grasp_quality(grasp, &quality), "quality")) goto done;
  printf("%zu contacts with the object\n", contacts);
  printf("epsilon %.7g\nvolume %.7g\nforce closure %s\n", quality.epsilon, quality.volume,
         quality.force_closure ? "yes" : "no");
  failed = 0;
done:
  graspkit_grasp_free(grasp);
  graspkit_world_free(world);
  return failed;
}
