/* graspkit.h compiled as C99 with -pedantic -Wall -Wextra -Werror (tests/CMakeLists.txt): the
 * build fails when the header stops being plain C. */
#include "graspkit.h"

/* Every struct is complete and usable in C. */
int graspkit_header_check(void) {
  graspkit_pose pose = {{0, 0, 0}, {1, 0, 0, 0}};
  graspkit_body_ref ref = {GRASPKIT_LINK, 0, -1, -1};
  graspkit_ray ray = {{0, 0, 0}, {0, 0, 1}, 0, 1};
  graspkit_ray_hit hit;
  graspkit_contact contact;
  graspkit_quality quality;
  graspkit_plan_options plan;
  graspkit_planned_grasp planned;
  graspkit_script_options script;
  graspkit_load_options load;
  graspkit_autograsp_result closed;
  (void)hit;
  (void)contact;
  (void)quality;
  (void)plan;
  (void)planned;
  (void)script;
  (void)load;
  (void)closed;
  return (int)(pose.rotation[0] + ref.kind + ray.tmax) + GRASPKIT_ABI_VERSION;
}
