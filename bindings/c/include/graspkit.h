/* graspkit.h: the C ABI of graspkit, for host programs and other languages (the Rust crate in
 * bindings/rust is built on it).
 *
 * Conventions, the same for every function:
 *  - Every function but the version and error queries returns a graspkit_status. On anything
 *    but GRASPKIT_OK the outputs are left untouched and graspkit_last_error() holds a message
 *    naming the file, line and element where the input was wrong (graspkit_last_error_file(),
 *    _line() and _element() give the parts). The message is per thread and lasts until the
 *    thread's next graspkit call.
 *  - No C++ exception ever crosses this interface; a null handle or a null pointer where one is
 *    required is GRASPKIT_ERROR_INVALID_ARGUMENT, never a crash.
 *  - Ownership: a function named *_new, *_load, *_clone, *_analyze or *_plan hands the caller a
 *    handle, which the caller releases with the matching *_free (free of NULL does nothing).
 *    Arrays are always the caller's: the caller passes the array and its length. Strings are
 *    copied into the caller's buffer: `capacity` bytes at most, always NUL-terminated when
 *    capacity > 0, and `*length` (when not NULL) gets the whole length without the NUL; a
 *    string that did not fit returns GRASPKIT_ERROR_BUFFER_TOO_SMALL with what fits written.
 *  - Threads: a handle is used by one thread at a time; different handles may be used from
 *    different threads at once (a world clone per thread, as the C++ API does).
 *  - Units are GraspIt!'s: millimetres, radians (mm for prismatic DOFs), grams. Poses are a
 *    translation and a unit quaternion (w, x, y, z) of a frame in the world.
 *
 * Indices: bodies are numbered 0..count-1 in the order of the world (obstacles and graspable
 * bodies as the world file lists them), robots likewise, DOFs in the robot file's order. A
 * solid (anything a ray can hit) is a graspkit_body_ref.
 */
#ifndef GRASPKIT_H
#define GRASPKIT_H

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32)
#define GRASPKIT_C_API
#else
#define GRASPKIT_C_API __attribute__((visibility("default")))
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* The ABI's version: raised whenever a signature, a struct layout or an enum value changes. */
#define GRASPKIT_ABI_VERSION 3

typedef enum graspkit_status {
  GRASPKIT_OK = 0,
  GRASPKIT_ERROR_INVALID_ARGUMENT = 1, /* a null handle or pointer, a wrong array length */
  GRASPKIT_ERROR_OUT_OF_RANGE = 2,     /* an index that names nothing */
  GRASPKIT_ERROR_NOT_FOUND = 3,        /* a name that names nothing */
  GRASPKIT_ERROR_INPUT = 4,            /* bad input: a missing or malformed file, NaN, ... */
  GRASPKIT_ERROR_BUFFER_TOO_SMALL = 5, /* a string was cut to the caller's buffer */
  GRASPKIT_ERROR_SCRIPT = 6,           /* a Lua script failed (its traceback is the message) */
  GRASPKIT_ERROR_INTERNAL = 7          /* a bug, or out of memory */
} graspkit_status;

/* ---- Versions and errors ------------------------------------------------------------------ */

/* GRASPKIT_ABI_VERSION of the library actually loaded (compare with the header's). */
GRASPKIT_C_API uint32_t graspkit_abi_version(void);
/* The engine's version, e.g. "0.1.0"; a static string. */
GRASPKIT_C_API const char* graspkit_version(void);
/* The last failure on this thread: the whole message ("file:line: <element>: what"), or "". */
GRASPKIT_C_API const char* graspkit_last_error(void);
/* Its parts: the file ("" when none), the line (0 when unknown), the element ("" when none). */
GRASPKIT_C_API const char* graspkit_last_error_file(void);
GRASPKIT_C_API int graspkit_last_error_line(void);
GRASPKIT_C_API const char* graspkit_last_error_element(void);
/* A short name of a status, e.g. "input error"; a static string. */
GRASPKIT_C_API const char* graspkit_status_name(int32_t status);

/* ---- Log ------------------------------------------------------------------------------------ */

typedef enum graspkit_log_level { GRASPKIT_LOG_WARNING = 1 } graspkit_log_level;

/* Receives every warning the engine gives (suspicious input that still loads). Called from the
 * thread that caused it. `kind` names what the warning is about, as `graspkit --no-warn` spells
 * it: "unknown-element", "geometry", "mass", "robot", "eigengrasp", "virtual-contact", "plugin",
 * "collision" or "script". `file` and `element` are "" when unknown, `line` 0. */
typedef void (*graspkit_log_fn)(graspkit_log_level level, const char* kind, const char* file,
                                int line, const char* element, const char* message, void* user);
/* Installs `fn` (NULL restores the default: "graspkit: warning: ..." on stderr; the library
 * never writes to stdout). `user` is passed back to every call. */
GRASPKIT_C_API graspkit_status graspkit_set_log_callback(graspkit_log_fn fn, void* user);

/* ---- Plain data ----------------------------------------------------------------------------- */

typedef struct graspkit_pose {
  double translation[3]; /* mm */
  double rotation[4];    /* unit quaternion w, x, y, z */
} graspkit_pose;

typedef enum graspkit_body_kind {
  GRASPKIT_BODY = 0, /* a free body: index is the body index */
  GRASPKIT_LINK = 1, /* a robot link: index is the robot, chain/link the link (-1/-1: palm) */
  GRASPKIT_MOUNT = 2 /* a connection's mount piece: index is the connection */
} graspkit_body_kind;

typedef struct graspkit_body_ref {
  int32_t kind; /* a graspkit_body_kind */
  int32_t index;
  int32_t chain;
  int32_t link;
} graspkit_body_ref;

/* ---- Worlds --------------------------------------------------------------------------------- */

typedef struct graspkit_world graspkit_world;

typedef struct graspkit_load_options {
  const char* const* roots; /* folders searched first for a world's <filename>s (--root) */
  size_t root_count;
  int generic_robots; /* nonzero: a robot of an unknown type loads as a generic hand */
  /* URDF hands, as graspkit's flags of the same names (all may be NULL / 0): */
  const char* const* package_paths; /* folders holding the packages package:// names */
  size_t package_path_count;
  const char* palm;          /* the link taken as the palm (NULL: the root link) */
  const char* urdf_material; /* every link's material (NULL: rubber) */
  const char* srdf;          /* <disable_collisions> pairs (NULL: the .srdf beside the URDF) */
  /* closing[i] for DOF i of close_count: +1 closes towards the upper limit, -1 the lower, 0 as
   * the file or the inferred direction says */
  const int32_t* closing;
  size_t close_count;
} graspkit_load_options;

/* An empty world. */
GRASPKIT_C_API graspkit_status graspkit_world_new(graspkit_world** world);
/* Loads a World, Robot or Body XML file (a Robot file gives a world of one robot, a Body file a
 * world of one graspable body). `options` may be NULL. */
GRASPKIT_C_API graspkit_status graspkit_world_load(const char* path,
                                                   const graspkit_load_options* options,
                                                   graspkit_world** world);
/* A copy sharing the meshes: cheap. */
GRASPKIT_C_API graspkit_status graspkit_world_clone(const graspkit_world* world,
                                                    graspkit_world** clone);
/* Saves as GraspIt! writes world files, atomically: a failed save leaves no partial file. Model
 * files are named so that the saved world loads from any working folder (relative to its folder,
 * or absolute). */
GRASPKIT_C_API graspkit_status graspkit_world_save(const graspkit_world* world, const char* path);
/* Adds the bodies and robots of a Body, Robot or World file; `first_body` and `first_robot`
 * (either may be NULL) get the index of the first one added (the count before the call). */
GRASPKIT_C_API graspkit_status graspkit_world_add_file(graspkit_world* world, const char* path,
                                                       const graspkit_load_options* options,
                                                       int32_t* first_body, int32_t* first_robot);
GRASPKIT_C_API void graspkit_world_free(graspkit_world* world);
/* Removes free body `body` (an obstacle or graspable body); later bodies move down one index. */
GRASPKIT_C_API graspkit_status graspkit_world_remove_body(graspkit_world* world, int32_t body);

/* ---- Bodies --------------------------------------------------------------------------------- */

GRASPKIT_C_API graspkit_status graspkit_world_body_count(const graspkit_world* world,
                                                         int32_t* count);
/* GRASPKIT_ERROR_NOT_FOUND when no body has that name. */
GRASPKIT_C_API graspkit_status graspkit_world_find_body(const graspkit_world* world,
                                                        const char* name, int32_t* body);
GRASPKIT_C_API graspkit_status graspkit_body_name(const graspkit_world* world, int32_t body,
                                                  char* buffer, size_t capacity, size_t* length);
/* 1 for a graspable (dynamic) body, 0 for an obstacle. */
GRASPKIT_C_API graspkit_status graspkit_body_is_graspable(const graspkit_world* world, int32_t body,
                                                          int* graspable);
/* Mass in grams, and the centre of gravity in the body frame (mm; `cog` may be NULL). */
GRASPKIT_C_API graspkit_status graspkit_body_mass(const graspkit_world* world, int32_t body,
                                                  double* mass, double cog[3]);
GRASPKIT_C_API graspkit_status graspkit_body_get_pose(const graspkit_world* world, int32_t body,
                                                      graspkit_pose* pose);
/* The quaternion is normalised; a zero or non-finite one is GRASPKIT_ERROR_INPUT. */
GRASPKIT_C_API graspkit_status graspkit_body_set_pose(graspkit_world* world, int32_t body,
                                                      const graspkit_pose* pose);
/* The name of any solid: a body's, "<robot>_palm", "<robot>_chain<c>_link<l>", "<robot>_mount". */
GRASPKIT_C_API graspkit_status graspkit_body_ref_name(const graspkit_world* world,
                                                      const graspkit_body_ref* ref, char* buffer,
                                                      size_t capacity, size_t* length);

/* ---- Robots --------------------------------------------------------------------------------- */

GRASPKIT_C_API graspkit_status graspkit_world_robot_count(const graspkit_world* world,
                                                          int32_t* count);
GRASPKIT_C_API graspkit_status graspkit_world_find_robot(const graspkit_world* world,
                                                         const char* name, int32_t* robot);
/* The world's first robot that is a hand (GraspIt!'s current hand); NOT_FOUND when none is. */
GRASPKIT_C_API graspkit_status graspkit_world_first_hand(const graspkit_world* world,
                                                         int32_t* robot);
GRASPKIT_C_API graspkit_status graspkit_robot_name(const graspkit_world* world, int32_t robot,
                                                   char* buffer, size_t capacity, size_t* length);
GRASPKIT_C_API graspkit_status graspkit_robot_dof_count(const graspkit_world* world, int32_t robot,
                                                        int32_t* count);
/* `count` must be the robot's DOF count. */
GRASPKIT_C_API graspkit_status graspkit_robot_get_dofs(const graspkit_world* world, int32_t robot,
                                                       double* values, size_t count);
/* Sets every DOF (clamped into its range; mounted robots follow). NaN is GRASPKIT_ERROR_INPUT. */
GRASPKIT_C_API graspkit_status graspkit_robot_set_dofs(graspkit_world* world, int32_t robot,
                                                       const double* values, size_t count);
GRASPKIT_C_API graspkit_status graspkit_robot_dof_limits(const graspkit_world* world, int32_t robot,
                                                         double* min, double* max, size_t count);
/* The base (palm) pose; setting it moves every robot mounted on this one. */
GRASPKIT_C_API graspkit_status graspkit_robot_get_pose(const graspkit_world* world, int32_t robot,
                                                       graspkit_pose* pose);
GRASPKIT_C_API graspkit_status graspkit_robot_set_pose(graspkit_world* world, int32_t robot,
                                                       const graspkit_pose* pose);
GRASPKIT_C_API graspkit_status graspkit_robot_chain_count(const graspkit_world* world,
                                                          int32_t robot, int32_t* count);
GRASPKIT_C_API graspkit_status graspkit_robot_link_count(const graspkit_world* world, int32_t robot,
                                                         int32_t chain, int32_t* count);
/* The world pose of link `link` of chain `chain`; chain = link = -1 is the palm. */
GRASPKIT_C_API graspkit_status graspkit_robot_link_pose(const graspkit_world* world, int32_t robot,
                                                        int32_t chain, int32_t link,
                                                        graspkit_pose* pose);

/* ---- Autograsp and grasp analysis ----------------------------------------------------------- */

typedef enum graspkit_motion_end {
  GRASPKIT_MOTION_SETTLED = 0,
  GRASPKIT_MOTION_CONTACT = 1,
  GRASPKIT_MOTION_ITERATION_LIMIT = 2,
  GRASPKIT_MOTION_INTERPOLATION_ERROR = 3,
  GRASPKIT_MOTION_NO_CONTACT = 4
} graspkit_motion_end;

typedef struct graspkit_autograsp_result {
  int32_t end;   /* a graspkit_motion_end */
  int32_t steps; /* steps taken */
} graspkit_autograsp_result;

/* Closes the hand as its robot type closes (GraspIt!'s autograsp); the world changes. `result`
 * may be NULL. */
GRASPKIT_C_API graspkit_status graspkit_robot_autograsp(graspkit_world* world, int32_t robot,
                                                        graspkit_autograsp_result* result);

typedef enum graspkit_wrench_space {
  GRASPKIT_GWS_L1 = 0,  /* GraspIt!'s default: the hull of the contacts' unit wrenches */
  GRASPKIT_GWS_LINF = 1 /* the Minkowski sum of the contacts' wrench sets */
} graspkit_wrench_space;

typedef enum graspkit_contact_model {
  GRASPKIT_CONTACT_FRICTIONLESS = 0,
  GRASPKIT_CONTACT_POINT = 1,
  GRASPKIT_CONTACT_SOFT_FINGER = 2
} graspkit_contact_model;

typedef struct graspkit_contact {
  graspkit_body_ref link; /* the hand's solid */
  graspkit_body_ref body; /* the other solid */
  double position[3];     /* on the hand's link, world, mm */
  double normal[3];       /* unit, into the link */
  double mu;              /* friction coefficient of the two materials */
  double torsion;         /* soft fingers: GraspIt!'s e_tau, mm; 0 otherwise */
  int32_t model;          /* a graspkit_contact_model */
} graspkit_contact;

typedef struct graspkit_quality {
  double epsilon; /* -1 without force closure or when the hull failed */
  double volume;  /* 0 when the hull failed */
  int force_closure;
} graspkit_quality;

typedef struct graspkit_grasp graspkit_grasp;

/* The hand's contacts with body `object` as the world stands, and their quality. `wrench_space`
 * is a graspkit_wrench_space (an int32_t, as every enum the ABI reads, so that any value a caller
 * passes is defined; unknown ones are refused). */
GRASPKIT_C_API graspkit_status graspkit_grasp_analyze(const graspkit_world* world, int32_t robot,
                                                      int32_t object, int32_t wrench_space,
                                                      graspkit_grasp** grasp);
GRASPKIT_C_API graspkit_status graspkit_grasp_quality(const graspkit_grasp* grasp,
                                                      graspkit_quality* quality);
GRASPKIT_C_API graspkit_status graspkit_grasp_contact_count(const graspkit_grasp* grasp,
                                                            size_t* count);
/* Copies min(capacity, count) contacts; `copied` (may be NULL) gets how many. */
GRASPKIT_C_API graspkit_status graspkit_grasp_contacts(const graspkit_grasp* grasp,
                                                       graspkit_contact* contacts, size_t capacity,
                                                       size_t* copied);
/* Why the wrench space could not be built ("" when it was). */
GRASPKIT_C_API graspkit_status graspkit_grasp_failure(const graspkit_grasp* grasp, char* buffer,
                                                      size_t capacity, size_t* length);
GRASPKIT_C_API void graspkit_grasp_free(graspkit_grasp* grasp);

/* ---- Rays and nearest points ---------------------------------------------------------------- */

/* An Embree scene of a world's solids at their poses. Build it once, query it many times;
 * after the world moves, graspkit_ray_scene_update re-reads the poses. */
typedef struct graspkit_ray_scene graspkit_ray_scene;

typedef struct graspkit_ray {
  double origin[3];    /* world, mm */
  double direction[3]; /* any non-zero length */
  double tmin;         /* mm, >= 0 */
  double tmax;         /* mm; INFINITY for no limit */
} graspkit_ray;

typedef struct graspkit_ray_hit {
  int32_t hit; /* 0: the ray met nothing, the rest is unset */
  int32_t triangle;
  graspkit_body_ref body;
  double point[3];  /* world, mm */
  double normal[3]; /* the triangle's counter-clockwise normal, unit */
  double distance;  /* mm from the origin (from the query point for nearest points) */
} graspkit_ray_hit;

/* include_links = 0 leaves the robots' links out (casting at what a hand will grasp). */
GRASPKIT_C_API graspkit_status graspkit_ray_scene_new(const graspkit_world* world,
                                                      int include_links,
                                                      graspkit_ray_scene** scene);
GRASPKIT_C_API graspkit_status graspkit_ray_scene_update(graspkit_ray_scene* scene,
                                                         const graspkit_world* world);
/* hits[i] answers rays[i]; both arrays hold `count`. A bad ray (NaN, zero direction, tmin < 0)
 * fails the whole call before any ray is traced. */
GRASPKIT_C_API graspkit_status graspkit_ray_scene_intersect(const graspkit_ray_scene* scene,
                                                            const graspkit_ray* rays,
                                                            graspkit_ray_hit* hits, size_t count);
/* For each of `count` points (xyz, mm, packed), the nearest surface point within max_distance
 * (INFINITY for any); nearest[i].hit = 0 when none is that close. */
GRASPKIT_C_API graspkit_status graspkit_ray_scene_nearest(const graspkit_ray_scene* scene,
                                                          const double* points, size_t count,
                                                          double max_distance,
                                                          graspkit_ray_hit* nearest);
GRASPKIT_C_API void graspkit_ray_scene_free(graspkit_ray_scene* scene);

/* ---- Planning ------------------------------------------------------------------------------- */

typedef struct graspkit_plan_options {
  const char* planner; /* "simann" (default), "approach", or a plugin's */
  const char* energy;  /* "contact" (default), "potential-quality", ... */
  int64_t steps;       /* the budget in steps; 0 with seconds = 0 means 40000 */
  double seconds;      /* the budget in wall seconds, when steps is 0 */
  uint64_t seed;
  int32_t threads;     /* 0: one per core */
  int32_t top;         /* how many grasps to keep */
  const char* mode;    /* simann: "restarts" or "anneal"; NULL: restarts (other planners: NULL) */
  const char* space;   /* hand position space: "axis-angle" (NULL), "complete", ... */
  const char* posture; /* posture space: "eigen" (NULL) or "dof" */
} graspkit_plan_options;

typedef struct graspkit_planned_grasp {
  graspkit_pose pregrasp; /* the hand as the planner left it, world */
  graspkit_pose closed;   /* after autograsp, world */
  double energy;
  double epsilon;
  double volume;
  int32_t contacts;
  int32_t force_closure;
} graspkit_planned_grasp;

typedef struct graspkit_plan graspkit_plan;

/* The defaults, the same as every front end's (graspkit plan, Lua, Python): simann in restarts
 * mode, contact energy, 40000 steps, seed 1, one thread per core, top 20, axis-angle, eigen. */
GRASPKIT_C_API graspkit_status graspkit_plan_options_default(graspkit_plan_options* options);
/* Plans grasps of body `object` with robot `robot` (the world is not changed), closes the hand
 * on each and measures them, best first. `options` may be NULL for the defaults. */
GRASPKIT_C_API graspkit_status graspkit_plan_grasps(const graspkit_world* world, int32_t robot,
                                                    int32_t object,
                                                    const graspkit_plan_options* options,
                                                    graspkit_plan** plan);
GRASPKIT_C_API graspkit_status graspkit_plan_count(const graspkit_plan* plan, size_t* count);
GRASPKIT_C_API graspkit_status graspkit_plan_grasp(const graspkit_plan* plan, size_t index,
                                                   graspkit_planned_grasp* grasp);
/* The closed DOF values of grasp `index`; `count` must be the robot's DOF count. */
GRASPKIT_C_API graspkit_status graspkit_plan_grasp_dofs(const graspkit_plan* plan, size_t index,
                                                        double* values, size_t count);
/* A new world (a clone of the planned one) with the hand closed as grasp `index` was measured:
 * analysed or saved, it gives the same contacts, epsilon and volume. */
GRASPKIT_C_API graspkit_status graspkit_plan_grasp_world(const graspkit_plan* plan, size_t index,
                                                         graspkit_world** world);
GRASPKIT_C_API void graspkit_plan_free(graspkit_plan* plan);

/* ---- Dynamics and validation ---------------------------------------------------------------- */

typedef struct graspkit_step_report {
  double time; /* the world's time after the step, s */
  int32_t contacts;
  int32_t active_contacts;
  int32_t joint_limits;
} graspkit_step_report;

/* Advances the world's dynamics by dt seconds (0: the default, 0.0025). `report` may be NULL. A
 * state the step cannot continue from is GRASPKIT_ERROR_INPUT with the reason. */
GRASPKIT_C_API graspkit_status graspkit_world_step(graspkit_world* world, double dt,
                                                   graspkit_step_report* report);

typedef struct graspkit_simulation_options {
  double seconds;    /* simulated time, s */
  double dt;         /* time step, s */
  int use_gravity;   /* nonzero: set gravity first; 0: the world's own */
  double gravity[3]; /* mm/s^2 */
  int autograsp;     /* nonzero: drive the first hand's DOFs towards their closing limits */
  int32_t every;     /* steps between calls of `frame` */
  /* Called with the world before the first step and after every `every` steps (may be NULL). */
  void (*frame)(const graspkit_world* world, void* user);
  void* user;
} graspkit_simulation_options;

typedef struct graspkit_simulation_result {
  int completed; /* 0: the simulation stopped on a bad state (graspkit_simulation_stop_reason) */
  int32_t steps;
  double time;
  graspkit_step_report last;
} graspkit_simulation_result;

/* The defaults, as graspkit simulate's: 1 s, dt 0.0025, the world's gravity, every 10 steps. */
GRASPKIT_C_API graspkit_status
graspkit_simulation_options_default(graspkit_simulation_options* options);
/* Steps the world as graspkit simulate does; `options` may be NULL. A simulation that blows up
 * is not an error: `completed` is 0 and graspkit_last_error says why. */
GRASPKIT_C_API graspkit_status graspkit_world_simulate(graspkit_world* world,
                                                       const graspkit_simulation_options* options,
                                                       graspkit_simulation_result* result);

typedef struct graspkit_direction_result {
  double direction[3]; /* unit, world frame: +x, -x, +y, -y, +z, -z in turn */
  int held;
  double slip;    /* mm, the object's largest travel relative to the palm */
  double turn;    /* rad */
  double seconds; /* simulated */
} graspkit_direction_result;

typedef struct graspkit_validation {
  int held; /* every direction held */
  int32_t directions_held;
  graspkit_direction_result directions[6];
  double settle_seconds; /* simulated: the squeeze before the pulls */
} graspkit_validation;

/* Labels the grasp the world holds (its first hand closed on its first graspable body) as
 * graspkit validate does; `seconds` per direction (0: 2). The world is not changed. */
GRASPKIT_C_API graspkit_status graspkit_validate(const graspkit_world* world, double seconds,
                                                 graspkit_validation* validation);

/* ---- Pictures and generated objects --------------------------------------------------------- */

typedef struct graspkit_render_options {
  int32_t width;
  int32_t height;
  const char* camera; /* auto, world, iso, +x, -x, +y, -y, +z, -z (NULL: auto) */
  int contacts;       /* nonzero: mark the first hand's contacts with the first graspable body */
  int32_t samples;    /* per pixel along each axis, 1..4 */
} graspkit_render_options;

/* 640 x 480, auto camera, no contacts, 1 sample: graspkit render's defaults. */
GRASPKIT_C_API graspkit_status graspkit_render_options_default(graspkit_render_options* options);
/* Draws the world as graspkit render does into `rgb` (height rows of width RGB pixels, top row
 * first: capacity >= width * height * 3 bytes); `png` (may be NULL) also writes a PNG there. */
GRASPKIT_C_API graspkit_status graspkit_world_render(const graspkit_world* world,
                                                     const graspkit_render_options* options,
                                                     uint8_t* rgb, size_t capacity,
                                                     const char* png);

/* Writes object `index` of the set `seed` describes (graspkit objects' default sizes, density
 * and material, every kind in turn) into `folder` as NAME.off and NAME.xml; `xml_path` gets the
 * Body XML's path (as graspkit_body_name copies strings). */
GRASPKIT_C_API graspkit_status graspkit_generate_object(const char* folder, uint64_t seed,
                                                        size_t index, char* xml_path,
                                                        size_t capacity, size_t* length);

/* ---- Grasp datasets ------------------------------------------------------------------------- */

typedef struct graspkit_dataset graspkit_dataset;

typedef struct graspkit_dataset_options {
  int32_t grasps; /* the best list's size */
  int64_t steps;  /* the planner's budget (0: 40000) */
  uint64_t seed;
  int validate; /* nonzero: label each grasp physically */
  double validate_seconds;
} graspkit_dataset_options;

typedef struct graspkit_dataset_grasp {
  graspkit_pose pregrasp; /* the hand, open, in the object's frame */
  graspkit_pose grasp;    /* the hand, closed, in the object's frame */
  double epsilon;
  double volume;
  int force_closure;
  int held; /* 1 held, 0 not, -1 not validated */
  int32_t contacts;
} graspkit_dataset_grasp;

/* graspkit batch's defaults for one object: 20 grasps, 40000 steps, seed 1, not validated. */
GRASPKIT_C_API graspkit_status graspkit_dataset_options_default(graspkit_dataset_options* options);
/* Plans one object's dataset as graspkit batch does: `hand` a robot file, `object` a body file,
 * the object at the origin. `load` and `options` may be NULL. */
GRASPKIT_C_API graspkit_status graspkit_dataset_plan(const char* hand, const char* object,
                                                     const graspkit_load_options* load,
                                                     const graspkit_dataset_options* options,
                                                     graspkit_dataset** dataset);
/* Reads a dataset file; writes one, atomically. */
GRASPKIT_C_API graspkit_status graspkit_dataset_load(const char* path, graspkit_dataset** dataset);
GRASPKIT_C_API graspkit_status graspkit_dataset_save(const graspkit_dataset* dataset,
                                                     const char* path);
GRASPKIT_C_API graspkit_status graspkit_dataset_count(const graspkit_dataset* dataset,
                                                      size_t* count);
GRASPKIT_C_API graspkit_status graspkit_dataset_get_grasp(const graspkit_dataset* dataset,
                                                          size_t index,
                                                          graspkit_dataset_grasp* grasp);
GRASPKIT_C_API void graspkit_dataset_free(graspkit_dataset* dataset);

/* ---- Lua scenarios -------------------------------------------------------------------------- */

typedef struct graspkit_script_options {
  const char* const* roots; /* model roots (readable by the script) */
  size_t root_count;
  const char* const* args; /* arg[1], arg[2], ... */
  size_t arg_count;
  double timeout_seconds; /* 0: none */
  int unsafe;             /* nonzero lifts the sandbox */
} graspkit_script_options;

/* Runs a Lua scenario (graspkit run's sandbox and module). `exit_status` gets the script's
 * os.exit status (0 when it ran to its end). A script error is GRASPKIT_ERROR_SCRIPT with the
 * traceback as the message, and exit_status 1. `options` may be NULL. */
GRASPKIT_C_API graspkit_status graspkit_run_script(const char* path,
                                                   const graspkit_script_options* options,
                                                   int* exit_status);

/* ---- Plugins -------------------------------------------------------------------------------- */

/* Lists every plugin on the search path as the probe's child process found it (none is loaded
 * into this process) and counts them (loadable or failed); the list is then read with
 * graspkit_plugin_info. */
GRASPKIT_C_API graspkit_status graspkit_plugins_scan(size_t* count);
/* Loads one plugin file. */
GRASPKIT_C_API graspkit_status graspkit_plugin_load(const char* path);
/* Plugin `index` of the last scan: its name ("" when unreadable), whether it loaded, and, for a
 * failed one, why (into `error`, which may be NULL with error_capacity 0). */
GRASPKIT_C_API graspkit_status graspkit_plugin_info(size_t index, char* name, size_t name_capacity,
                                                    int* loaded, char* error,
                                                    size_t error_capacity);
/* The folders searched, colon-separated. */
GRASPKIT_C_API graspkit_status graspkit_plugin_search_path(char* buffer, size_t capacity,
                                                           size_t* length);

#ifdef __cplusplus
}
#endif

#endif /* GRASPKIT_H */
