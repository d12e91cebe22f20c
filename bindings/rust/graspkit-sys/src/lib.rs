//! Raw declarations of graspkit's C ABI, `bindings/c/include/graspkit.h`, one for one. Every
//! function returns a [`graspkit_status`]; the header states the rules (ownership, strings,
//! threads). Use the `graspkit` crate for a safe interface.
#![allow(non_camel_case_types)]

use std::os::raw::{c_char, c_double, c_int, c_void};

/// The ABI version these declarations follow (`GRASPKIT_ABI_VERSION`).
pub const GRASPKIT_ABI_VERSION: u32 = 3;

/// `graspkit_status`.
pub type graspkit_status = c_int;
pub const GRASPKIT_OK: graspkit_status = 0;
pub const GRASPKIT_ERROR_INVALID_ARGUMENT: graspkit_status = 1;
pub const GRASPKIT_ERROR_OUT_OF_RANGE: graspkit_status = 2;
pub const GRASPKIT_ERROR_NOT_FOUND: graspkit_status = 3;
pub const GRASPKIT_ERROR_INPUT: graspkit_status = 4;
pub const GRASPKIT_ERROR_BUFFER_TOO_SMALL: graspkit_status = 5;
pub const GRASPKIT_ERROR_SCRIPT: graspkit_status = 6;
pub const GRASPKIT_ERROR_INTERNAL: graspkit_status = 7;

pub type graspkit_log_level = c_int;
pub const GRASPKIT_LOG_WARNING: graspkit_log_level = 1;

pub type graspkit_log_fn = Option<
    unsafe extern "C" fn(
        level: graspkit_log_level,
        kind: *const c_char,
        file: *const c_char,
        line: c_int,
        element: *const c_char,
        message: *const c_char,
        user: *mut c_void,
    ),
>;

pub const GRASPKIT_BODY: i32 = 0;
pub const GRASPKIT_LINK: i32 = 1;
pub const GRASPKIT_MOUNT: i32 = 2;

pub const GRASPKIT_MOTION_SETTLED: i32 = 0;
pub const GRASPKIT_MOTION_CONTACT: i32 = 1;
pub const GRASPKIT_MOTION_ITERATION_LIMIT: i32 = 2;
pub const GRASPKIT_MOTION_INTERPOLATION_ERROR: i32 = 3;
pub const GRASPKIT_MOTION_NO_CONTACT: i32 = 4;

pub type graspkit_wrench_space = i32;
pub const GRASPKIT_GWS_L1: graspkit_wrench_space = 0;
pub const GRASPKIT_GWS_LINF: graspkit_wrench_space = 1;

pub const GRASPKIT_CONTACT_FRICTIONLESS: i32 = 0;
pub const GRASPKIT_CONTACT_POINT: i32 = 1;
pub const GRASPKIT_CONTACT_SOFT_FINGER: i32 = 2;

#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct graspkit_pose {
    pub translation: [c_double; 3],
    pub rotation: [c_double; 4],
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct graspkit_body_ref {
    pub kind: i32,
    pub index: i32,
    pub chain: i32,
    pub link: i32,
}

#[repr(C)]
pub struct graspkit_world {
    _opaque: [u8; 0],
}
#[repr(C)]
pub struct graspkit_grasp {
    _opaque: [u8; 0],
}
#[repr(C)]
pub struct graspkit_ray_scene {
    _opaque: [u8; 0],
}
#[repr(C)]
pub struct graspkit_plan {
    _opaque: [u8; 0],
}

#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct graspkit_load_options {
    pub roots: *const *const c_char,
    pub root_count: usize,
    pub generic_robots: c_int,
    pub package_paths: *const *const c_char,
    pub package_path_count: usize,
    pub palm: *const c_char,
    pub urdf_material: *const c_char,
    pub srdf: *const c_char,
    pub closing: *const i32,
    pub close_count: usize,
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct graspkit_autograsp_result {
    pub end: i32,
    pub steps: i32,
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct graspkit_contact {
    pub link: graspkit_body_ref,
    pub body: graspkit_body_ref,
    pub position: [c_double; 3],
    pub normal: [c_double; 3],
    pub mu: c_double,
    pub torsion: c_double,
    pub model: i32,
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct graspkit_quality {
    pub epsilon: c_double,
    pub volume: c_double,
    pub force_closure: c_int,
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct graspkit_ray {
    pub origin: [c_double; 3],
    pub direction: [c_double; 3],
    pub tmin: c_double,
    pub tmax: c_double,
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct graspkit_ray_hit {
    pub hit: i32,
    pub triangle: i32,
    pub body: graspkit_body_ref,
    pub point: [c_double; 3],
    pub normal: [c_double; 3],
    pub distance: c_double,
}

#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct graspkit_plan_options {
    pub planner: *const c_char,
    pub energy: *const c_char,
    pub steps: i64,
    pub seconds: c_double,
    pub seed: u64,
    pub threads: i32,
    pub top: i32,
    pub mode: *const c_char,
    pub space: *const c_char,
    pub posture: *const c_char,
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct graspkit_step_report {
    pub time: c_double,
    pub contacts: i32,
    pub active_contacts: i32,
    pub joint_limits: i32,
}

pub type graspkit_frame_fn =
    Option<unsafe extern "C" fn(world: *const graspkit_world, user: *mut c_void)>;

#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct graspkit_simulation_options {
    pub seconds: c_double,
    pub dt: c_double,
    pub use_gravity: c_int,
    pub gravity: [c_double; 3],
    pub autograsp: c_int,
    pub every: i32,
    pub frame: graspkit_frame_fn,
    pub user: *mut c_void,
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct graspkit_simulation_result {
    pub completed: c_int,
    pub steps: i32,
    pub time: c_double,
    pub last: graspkit_step_report,
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct graspkit_direction_result {
    pub direction: [c_double; 3],
    pub held: c_int,
    pub slip: c_double,
    pub turn: c_double,
    pub seconds: c_double,
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct graspkit_validation {
    pub held: c_int,
    pub directions_held: i32,
    pub directions: [graspkit_direction_result; 6],
    pub settle_seconds: c_double,
}

#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct graspkit_render_options {
    pub width: i32,
    pub height: i32,
    pub camera: *const c_char,
    pub contacts: c_int,
    pub samples: i32,
}

#[repr(C)]
pub struct graspkit_dataset {
    _private: [u8; 0],
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct graspkit_dataset_options {
    pub grasps: i32,
    pub steps: i64,
    pub seed: u64,
    pub validate: c_int,
    pub validate_seconds: c_double,
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct graspkit_dataset_grasp {
    pub pregrasp: graspkit_pose,
    pub grasp: graspkit_pose,
    pub epsilon: c_double,
    pub volume: c_double,
    pub force_closure: c_int,
    pub held: c_int,
    pub contacts: i32,
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct graspkit_planned_grasp {
    pub pregrasp: graspkit_pose,
    pub closed: graspkit_pose,
    pub energy: c_double,
    pub epsilon: c_double,
    pub volume: c_double,
    pub contacts: i32,
    pub force_closure: i32,
}

#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct graspkit_script_options {
    pub roots: *const *const c_char,
    pub root_count: usize,
    pub args: *const *const c_char,
    pub arg_count: usize,
    pub timeout_seconds: c_double,
    pub unsafe_: c_int,
}

extern "C" {
    pub fn graspkit_abi_version() -> u32;
    pub fn graspkit_version() -> *const c_char;
    pub fn graspkit_last_error() -> *const c_char;
    pub fn graspkit_last_error_file() -> *const c_char;
    pub fn graspkit_last_error_line() -> c_int;
    pub fn graspkit_last_error_element() -> *const c_char;
    pub fn graspkit_status_name(status: i32) -> *const c_char;
    pub fn graspkit_set_log_callback(f: graspkit_log_fn, user: *mut c_void) -> graspkit_status;

    pub fn graspkit_world_new(world: *mut *mut graspkit_world) -> graspkit_status;
    pub fn graspkit_world_load(
        path: *const c_char,
        options: *const graspkit_load_options,
        world: *mut *mut graspkit_world,
    ) -> graspkit_status;
    pub fn graspkit_world_clone(
        world: *const graspkit_world,
        clone: *mut *mut graspkit_world,
    ) -> graspkit_status;
    pub fn graspkit_world_save(
        world: *const graspkit_world,
        path: *const c_char,
    ) -> graspkit_status;
    pub fn graspkit_world_add_file(
        world: *mut graspkit_world,
        path: *const c_char,
        options: *const graspkit_load_options,
        first_body: *mut i32,
        first_robot: *mut i32,
    ) -> graspkit_status;
    pub fn graspkit_world_free(world: *mut graspkit_world);
    pub fn graspkit_world_remove_body(world: *mut graspkit_world, body: i32) -> graspkit_status;

    pub fn graspkit_world_body_count(
        world: *const graspkit_world,
        count: *mut i32,
    ) -> graspkit_status;
    pub fn graspkit_world_find_body(
        world: *const graspkit_world,
        name: *const c_char,
        body: *mut i32,
    ) -> graspkit_status;
    pub fn graspkit_body_name(
        world: *const graspkit_world,
        body: i32,
        buffer: *mut c_char,
        capacity: usize,
        length: *mut usize,
    ) -> graspkit_status;
    pub fn graspkit_body_is_graspable(
        world: *const graspkit_world,
        body: i32,
        graspable: *mut c_int,
    ) -> graspkit_status;
    pub fn graspkit_body_mass(
        world: *const graspkit_world,
        body: i32,
        mass: *mut c_double,
        cog: *mut c_double,
    ) -> graspkit_status;
    pub fn graspkit_body_get_pose(
        world: *const graspkit_world,
        body: i32,
        pose: *mut graspkit_pose,
    ) -> graspkit_status;
    pub fn graspkit_body_set_pose(
        world: *mut graspkit_world,
        body: i32,
        pose: *const graspkit_pose,
    ) -> graspkit_status;
    pub fn graspkit_body_ref_name(
        world: *const graspkit_world,
        body: *const graspkit_body_ref,
        buffer: *mut c_char,
        capacity: usize,
        length: *mut usize,
    ) -> graspkit_status;

    pub fn graspkit_world_robot_count(
        world: *const graspkit_world,
        count: *mut i32,
    ) -> graspkit_status;
    pub fn graspkit_world_find_robot(
        world: *const graspkit_world,
        name: *const c_char,
        robot: *mut i32,
    ) -> graspkit_status;
    pub fn graspkit_world_first_hand(
        world: *const graspkit_world,
        robot: *mut i32,
    ) -> graspkit_status;
    pub fn graspkit_robot_name(
        world: *const graspkit_world,
        robot: i32,
        buffer: *mut c_char,
        capacity: usize,
        length: *mut usize,
    ) -> graspkit_status;
    pub fn graspkit_robot_dof_count(
        world: *const graspkit_world,
        robot: i32,
        count: *mut i32,
    ) -> graspkit_status;
    pub fn graspkit_robot_get_dofs(
        world: *const graspkit_world,
        robot: i32,
        values: *mut c_double,
        count: usize,
    ) -> graspkit_status;
    pub fn graspkit_robot_set_dofs(
        world: *mut graspkit_world,
        robot: i32,
        values: *const c_double,
        count: usize,
    ) -> graspkit_status;
    pub fn graspkit_robot_dof_limits(
        world: *const graspkit_world,
        robot: i32,
        min: *mut c_double,
        max: *mut c_double,
        count: usize,
    ) -> graspkit_status;
    pub fn graspkit_robot_get_pose(
        world: *const graspkit_world,
        robot: i32,
        pose: *mut graspkit_pose,
    ) -> graspkit_status;
    pub fn graspkit_robot_set_pose(
        world: *mut graspkit_world,
        robot: i32,
        pose: *const graspkit_pose,
    ) -> graspkit_status;
    pub fn graspkit_robot_chain_count(
        world: *const graspkit_world,
        robot: i32,
        count: *mut i32,
    ) -> graspkit_status;
    pub fn graspkit_robot_link_count(
        world: *const graspkit_world,
        robot: i32,
        chain: i32,
        count: *mut i32,
    ) -> graspkit_status;
    pub fn graspkit_robot_link_pose(
        world: *const graspkit_world,
        robot: i32,
        chain: i32,
        link: i32,
        pose: *mut graspkit_pose,
    ) -> graspkit_status;

    pub fn graspkit_robot_autograsp(
        world: *mut graspkit_world,
        robot: i32,
        result: *mut graspkit_autograsp_result,
    ) -> graspkit_status;
    pub fn graspkit_grasp_analyze(
        world: *const graspkit_world,
        robot: i32,
        object: i32,
        wrench_space: graspkit_wrench_space,
        grasp: *mut *mut graspkit_grasp,
    ) -> graspkit_status;
    pub fn graspkit_grasp_quality(
        grasp: *const graspkit_grasp,
        quality: *mut graspkit_quality,
    ) -> graspkit_status;
    pub fn graspkit_grasp_contact_count(
        grasp: *const graspkit_grasp,
        count: *mut usize,
    ) -> graspkit_status;
    pub fn graspkit_grasp_contacts(
        grasp: *const graspkit_grasp,
        contacts: *mut graspkit_contact,
        capacity: usize,
        copied: *mut usize,
    ) -> graspkit_status;
    pub fn graspkit_grasp_failure(
        grasp: *const graspkit_grasp,
        buffer: *mut c_char,
        capacity: usize,
        length: *mut usize,
    ) -> graspkit_status;
    pub fn graspkit_grasp_free(grasp: *mut graspkit_grasp);

    pub fn graspkit_ray_scene_new(
        world: *const graspkit_world,
        include_links: c_int,
        scene: *mut *mut graspkit_ray_scene,
    ) -> graspkit_status;
    pub fn graspkit_ray_scene_update(
        scene: *mut graspkit_ray_scene,
        world: *const graspkit_world,
    ) -> graspkit_status;
    pub fn graspkit_ray_scene_intersect(
        scene: *const graspkit_ray_scene,
        rays: *const graspkit_ray,
        hits: *mut graspkit_ray_hit,
        count: usize,
    ) -> graspkit_status;
    pub fn graspkit_ray_scene_nearest(
        scene: *const graspkit_ray_scene,
        points: *const c_double,
        count: usize,
        max_distance: c_double,
        nearest: *mut graspkit_ray_hit,
    ) -> graspkit_status;
    pub fn graspkit_ray_scene_free(scene: *mut graspkit_ray_scene);

    pub fn graspkit_plan_options_default(options: *mut graspkit_plan_options) -> graspkit_status;
    pub fn graspkit_plan_grasps(
        world: *const graspkit_world,
        robot: i32,
        object: i32,
        options: *const graspkit_plan_options,
        plan: *mut *mut graspkit_plan,
    ) -> graspkit_status;
    pub fn graspkit_plan_count(plan: *const graspkit_plan, count: *mut usize) -> graspkit_status;
    pub fn graspkit_plan_grasp(
        plan: *const graspkit_plan,
        index: usize,
        grasp: *mut graspkit_planned_grasp,
    ) -> graspkit_status;
    pub fn graspkit_plan_grasp_dofs(
        plan: *const graspkit_plan,
        index: usize,
        values: *mut c_double,
        count: usize,
    ) -> graspkit_status;
    pub fn graspkit_plan_grasp_world(
        plan: *const graspkit_plan,
        index: usize,
        world: *mut *mut graspkit_world,
    ) -> graspkit_status;
    pub fn graspkit_plan_free(plan: *mut graspkit_plan);

    pub fn graspkit_world_step(
        world: *mut graspkit_world,
        dt: c_double,
        report: *mut graspkit_step_report,
    ) -> graspkit_status;
    pub fn graspkit_simulation_options_default(
        options: *mut graspkit_simulation_options,
    ) -> graspkit_status;
    pub fn graspkit_world_simulate(
        world: *mut graspkit_world,
        options: *const graspkit_simulation_options,
        result: *mut graspkit_simulation_result,
    ) -> graspkit_status;
    pub fn graspkit_validate(
        world: *const graspkit_world,
        seconds: c_double,
        validation: *mut graspkit_validation,
    ) -> graspkit_status;

    pub fn graspkit_render_options_default(options: *mut graspkit_render_options)
        -> graspkit_status;
    pub fn graspkit_world_render(
        world: *const graspkit_world,
        options: *const graspkit_render_options,
        rgb: *mut u8,
        capacity: usize,
        png: *const c_char,
    ) -> graspkit_status;
    pub fn graspkit_generate_object(
        folder: *const c_char,
        seed: u64,
        index: usize,
        xml_path: *mut c_char,
        capacity: usize,
        length: *mut usize,
    ) -> graspkit_status;

    pub fn graspkit_dataset_options_default(options: *mut graspkit_dataset_options)
        -> graspkit_status;
    pub fn graspkit_dataset_plan(
        hand: *const c_char,
        object: *const c_char,
        load: *const graspkit_load_options,
        options: *const graspkit_dataset_options,
        dataset: *mut *mut graspkit_dataset,
    ) -> graspkit_status;
    pub fn graspkit_dataset_load(
        path: *const c_char,
        dataset: *mut *mut graspkit_dataset,
    ) -> graspkit_status;
    pub fn graspkit_dataset_save(
        dataset: *const graspkit_dataset,
        path: *const c_char,
    ) -> graspkit_status;
    pub fn graspkit_dataset_count(dataset: *const graspkit_dataset, count: *mut usize)
        -> graspkit_status;
    pub fn graspkit_dataset_get_grasp(
        dataset: *const graspkit_dataset,
        index: usize,
        grasp: *mut graspkit_dataset_grasp,
    ) -> graspkit_status;
    pub fn graspkit_dataset_free(dataset: *mut graspkit_dataset);

    pub fn graspkit_run_script(
        path: *const c_char,
        options: *const graspkit_script_options,
        exit_status: *mut c_int,
    ) -> graspkit_status;

    pub fn graspkit_plugins_scan(count: *mut usize) -> graspkit_status;
    pub fn graspkit_plugin_load(path: *const c_char) -> graspkit_status;
    pub fn graspkit_plugin_info(
        index: usize,
        name: *mut c_char,
        name_capacity: usize,
        loaded: *mut c_int,
        error: *mut c_char,
        error_capacity: usize,
    ) -> graspkit_status;
    pub fn graspkit_plugin_search_path(
        buffer: *mut c_char,
        capacity: usize,
        length: *mut usize,
    ) -> graspkit_status;
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::mem::size_of;

    // Sizes worked out by hand from graspkit.h on a 64-bit target (doubles and pointers 8 bytes,
    // int32 4, padding to 8): a layout mismatch would corrupt memory silently.
    #[test]
    fn struct_layouts_match_the_header() {
        assert_eq!(size_of::<graspkit_pose>(), 7 * 8);
        assert_eq!(size_of::<graspkit_body_ref>(), 16);
        assert_eq!(size_of::<graspkit_load_options>(), 24 + 7 * 8);
        assert_eq!(size_of::<graspkit_autograsp_result>(), 8);
        assert_eq!(size_of::<graspkit_contact>(), 32 + 6 * 8 + 2 * 8 + 8);
        assert_eq!(size_of::<graspkit_quality>(), 24);
        assert_eq!(size_of::<graspkit_ray>(), 64);
        assert_eq!(size_of::<graspkit_ray_hit>(), 8 + 16 + 56);
        assert_eq!(size_of::<graspkit_plan_options>(), 48 + 3 * 8);
        assert_eq!(size_of::<graspkit_step_report>(), 24);
        assert_eq!(size_of::<graspkit_simulation_options>(), 72);
        assert_eq!(size_of::<graspkit_simulation_result>(), 16 + 24);
        assert_eq!(size_of::<graspkit_direction_result>(), 56);
        assert_eq!(size_of::<graspkit_validation>(), 8 + 6 * 56 + 8);
        assert_eq!(size_of::<graspkit_render_options>(), 24);
        assert_eq!(size_of::<graspkit_dataset_options>(), 40);
        assert_eq!(size_of::<graspkit_dataset_grasp>(), 2 * 56 + 32);
        assert_eq!(size_of::<graspkit_planned_grasp>(), 2 * 56 + 3 * 8 + 8);
        assert_eq!(size_of::<graspkit_script_options>(), 48);
    }

    #[test]
    fn the_library_is_the_abi_these_declarations_follow() {
        assert_eq!(unsafe { graspkit_abi_version() }, GRASPKIT_ABI_VERSION);
    }
}
