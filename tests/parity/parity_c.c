/* The parity request through the C ABI (tests/parity/parity_test.py runs it).
 * Usage: graspkit_parity_c PLANNER_WORLD ROOT GRASP_WORLD STEPS SEED TOP SECONDS HAND OUT
 * Prints one JSON object: plan, grasp, validation, simulation, dataset (parity_test.py's
 * schema). */

#include <graspkit.h>
#include <stdio.h>
#include <stdlib.h>

static void check(graspkit_status status, const char* what) {
  if (status == GRASPKIT_OK) return;
  fprintf(stderr, "%s: %s\n", what, graspkit_last_error());
  exit(1);
}

static void print_pose(const graspkit_pose* p) {
  printf("[%.17g, %.17g, %.17g, %.17g, %.17g, %.17g, %.17g]", p->translation[0], p->translation[1],
         p->translation[2], p->rotation[0], p->rotation[1], p->rotation[2], p->rotation[3]);
}

static graspkit_world* load(const char* path, const char* root) {
  graspkit_load_options options = {0};
  options.roots = &root;
  options.root_count = 1;
  graspkit_world* world = NULL;
  check(graspkit_world_load(path, &options, &world), path);
  return world;
}

static int32_t first_graspable(const graspkit_world* world) {
  int32_t count = 0;
  check(graspkit_world_body_count(world, &count), "body count");
  for (int32_t b = 0; b < count; ++b) {
    int graspable = 0;
    check(graspkit_body_is_graspable(world, b, &graspable), "graspable");
    if (graspable) return b;
  }
  fprintf(stderr, "no graspable body\n");
  exit(1);
}

int main(int argc, char** argv) {
  if (argc != 10) {
    fprintf(stderr, "usage: %s PLANNER_WORLD ROOT GRASP_WORLD STEPS SEED TOP SECONDS HAND OUT\n",
            argv[0]);
    return 2;
  }
  const char *planner_world = argv[1], *root = argv[2], *grasp_world = argv[3];
  const double seconds = atof(argv[7]);

  graspkit_world* world = load(planner_world, root);
  int32_t hand = 0;
  check(graspkit_world_first_hand(world, &hand), "first hand");
  graspkit_plan_options options;
  check(graspkit_plan_options_default(&options), "plan defaults");
  options.steps = atoll(argv[4]);
  options.seed = strtoull(argv[5], NULL, 10);
  options.top = atoi(argv[6]);
  graspkit_plan* plan = NULL;
  check(graspkit_plan_grasps(world, hand, first_graspable(world), &options, &plan), "plan");
  size_t count = 0;
  check(graspkit_plan_count(plan, &count), "plan count");
  printf("{\"plan\": [");
  for (size_t i = 0; i < count; ++i) {
    graspkit_planned_grasp g;
    check(graspkit_plan_grasp(plan, i, &g), "plan grasp");
    printf(
        "%s{\"epsilon\": %.17g, \"volume\": %.17g, \"contacts\": %d, \"force_closure\": %s, "
        "\"pose\": ",
        i ? ", " : "", g.epsilon, g.volume, g.contacts, g.force_closure ? "true" : "false");
    print_pose(&g.closed);
    printf("}");
  }
  printf("], ");
  graspkit_plan_free(plan);

  check(graspkit_robot_autograsp(world, hand, NULL), "autograsp");
  graspkit_grasp* grasp = NULL;
  check(graspkit_grasp_analyze(world, hand, first_graspable(world), GRASPKIT_GWS_L1, &grasp),
        "analyze");
  graspkit_quality quality;
  size_t contacts = 0;
  check(graspkit_grasp_quality(grasp, &quality), "quality");
  check(graspkit_grasp_contact_count(grasp, &contacts), "contacts");
  printf(
      "\"grasp\": {\"epsilon\": %.17g, \"volume\": %.17g, \"contacts\": %zu, "
      "\"force_closure\": %s}, ",
      quality.epsilon, quality.volume, contacts, quality.force_closure ? "true" : "false");
  graspkit_grasp_free(grasp);
  graspkit_world_free(world);

  graspkit_world* held = load(grasp_world, root);
  graspkit_validation validation;
  check(graspkit_validate(held, seconds, &validation), "validate");
  printf(
      "\"validation\": {\"held\": %s, \"directions_held\": %d, \"settle_seconds\": %.17g, "
      "\"slip\": [",
      validation.held ? "true" : "false", validation.directions_held, validation.settle_seconds);
  for (int k = 0; k < 6; ++k) printf("%s%.17g", k ? ", " : "", validation.directions[k].slip);
  printf("]}, ");
  graspkit_world_free(held);

  graspkit_world* moving = load(grasp_world, root);
  graspkit_simulation_options sim;
  check(graspkit_simulation_options_default(&sim), "simulation defaults");
  sim.seconds = seconds;
  sim.autograsp = 1;
  graspkit_simulation_result result;
  check(graspkit_world_simulate(moving, &sim, &result), "simulate");
  printf("\"simulation\": {\"completed\": %s, \"steps\": %d, \"time\": %.17g, \"bodies\": [",
         result.completed ? "true" : "false", result.steps, result.time);
  int32_t bodies = 0, robots = 0;
  check(graspkit_world_body_count(moving, &bodies), "body count");
  for (int32_t b = 0; b < bodies; ++b) {
    graspkit_pose pose;
    check(graspkit_body_get_pose(moving, b, &pose), "body pose");
    printf("%s", b ? ", " : "");
    print_pose(&pose);
  }
  printf("], \"dofs\": [");
  check(graspkit_world_robot_count(moving, &robots), "robot count");
  int first = 1;
  for (int32_t r = 0; r < robots; ++r) {
    int32_t n = 0;
    check(graspkit_robot_dof_count(moving, r, &n), "dof count");
    double values[64];
    if (n > 64) return 1;
    check(graspkit_robot_get_dofs(moving, r, values, (size_t)n), "dofs");
    for (int32_t d = 0; d < n; ++d, first = 0) printf("%s%.17g", first ? "" : ", ", values[d]);
  }
  printf("]}, ");
  graspkit_world_free(moving);

  /* One generated object's dataset: planned, saved, read back. */
  char object[4096], file[4200];
  check(graspkit_generate_object(argv[9], 2, 0, object, sizeof object, NULL), "generate");
  graspkit_dataset_options dataset_options;
  check(graspkit_dataset_options_default(&dataset_options), "dataset defaults");
  dataset_options.grasps = 3;
  dataset_options.steps = 1500;
  dataset_options.seed = 5;
  graspkit_dataset* planned = NULL;
  check(graspkit_dataset_plan(argv[8], object, NULL, &dataset_options, &planned), "dataset");
  snprintf(file, sizeof file, "%s/dataset.h5", argv[9]);
  check(graspkit_dataset_save(planned, file), "dataset save");
  graspkit_dataset_free(planned);
  graspkit_dataset* dataset = NULL;
  check(graspkit_dataset_load(file, &dataset), "dataset load");
  size_t grasps = 0;
  check(graspkit_dataset_count(dataset, &grasps), "dataset count");
  printf("\"dataset\": [");
  for (size_t i = 0; i < grasps; ++i) {
    graspkit_dataset_grasp g;
    check(graspkit_dataset_get_grasp(dataset, i, &g), "dataset grasp");
    printf("%s{\"epsilon\": %.17g, \"volume\": %.17g, \"force_closure\": %s, \"pose\": ",
           i ? ", " : "", g.epsilon, g.volume, g.force_closure ? "true" : "false");
    print_pose(&g.grasp);
    printf("}");
  }
  printf("]}\n");
  graspkit_dataset_free(dataset);
  return 0;
}
