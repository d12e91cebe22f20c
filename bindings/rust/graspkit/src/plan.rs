//! Grasp planning: a planner run on a world, each grasp closed and measured.

use std::ptr;

use graspkit_sys as sys;

use crate::error::{check, Result};
use crate::strings::c_string;
use crate::world::{Pose, World};

/// How to plan. `Default` is graspkit's: simann restarts, contact energy, 40000 steps, seed 1,
/// one thread per core, the best 20.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanOptions {
    /// "simann", "approach", or a plugin's planner.
    pub planner: String,
    /// "contact", "potential-quality", ...
    pub energy: String,
    /// The budget in steps (0: use `seconds`, or 40000 when that is 0 too).
    pub steps: i64,
    /// The budget in wall seconds, when `steps` is 0.
    pub seconds: f64,
    /// The random seed (a step budget gives the same grasps for the same seed).
    pub seed: u64,
    /// Threads (0: one per core).
    pub threads: i32,
    /// How many grasps to keep.
    pub top: i32,
    /// simann's mode, "restarts" or "anneal" (`None`: restarts; other planners have none).
    pub mode: Option<String>,
    /// The hand position space: "axis-angle", "complete", "ellipsoid", "approach".
    pub space: String,
    /// The posture space: "eigen" or "dof".
    pub posture: String,
}

impl Default for PlanOptions {
    /// graspkit's defaults, as the C ABI (and every other front end) has them.
    fn default() -> PlanOptions {
        let mut raw = std::mem::MaybeUninit::<sys::graspkit_plan_options>::zeroed();
        unsafe { sys::graspkit_plan_options_default(raw.as_mut_ptr()) };
        let raw = unsafe { raw.assume_init() };
        PlanOptions {
            planner: crate::error::text(raw.planner),
            energy: crate::error::text(raw.energy),
            steps: raw.steps,
            seconds: raw.seconds,
            seed: raw.seed,
            threads: raw.threads,
            top: raw.top,
            mode: None,
            space: crate::error::text(raw.space),
            posture: crate::error::text(raw.posture),
        }
    }
}

/// One planned grasp, closed and measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlannedGrasp {
    /// The hand as the planner left it.
    pub pregrasp: Pose,
    /// The hand after autograsp.
    pub closed: Pose,
    /// The search energy.
    pub energy: f64,
    /// L1 epsilon (-1 without force closure).
    pub epsilon: f64,
    /// L1 volume.
    pub volume: f64,
    /// Contacts with the object.
    pub contacts: i32,
    /// Whether it is force closure.
    pub force_closure: bool,
}

/// The grasps a planner found, best first (freed when dropped). `Send`, not `Sync`.
pub struct Plan {
    raw: *mut sys::graspkit_plan,
    grasps: Vec<PlannedGrasp>,
}

unsafe impl Send for Plan {}

impl Drop for Plan {
    fn drop(&mut self) {
        unsafe { sys::graspkit_plan_free(self.raw) }
    }
}

impl Plan {
    /// Plans grasps of body `object` with hand `robot` of `world` (which is not changed).
    pub fn run(world: &World, robot: i32, object: i32, options: &PlanOptions) -> Result<Plan> {
        let planner = c_string(&options.planner)?;
        let energy = c_string(&options.energy)?;
        let mode = options.mode.as_deref().map(c_string).transpose()?;
        let space = c_string(&options.space)?;
        let posture = c_string(&options.posture)?;
        let raw_options = sys::graspkit_plan_options {
            mode: mode.as_ref().map_or(ptr::null(), |m| m.as_ptr()),
            space: space.as_ptr(),
            posture: posture.as_ptr(),
            planner: planner.as_ptr(),
            energy: energy.as_ptr(),
            steps: options.steps,
            seconds: options.seconds,
            seed: options.seed,
            threads: options.threads,
            top: options.top,
        };
        let mut raw = ptr::null_mut();
        check(unsafe {
            sys::graspkit_plan_grasps(world.raw, robot, object, &raw_options, &mut raw)
        })?;
        let mut plan = Plan {
            raw,
            grasps: Vec::new(),
        };
        let mut count = 0usize;
        check(unsafe { sys::graspkit_plan_count(plan.raw, &mut count) })?;
        for i in 0..count {
            let mut g = sys::graspkit_planned_grasp::default();
            check(unsafe { sys::graspkit_plan_grasp(plan.raw, i, &mut g) })?;
            plan.grasps.push(PlannedGrasp {
                pregrasp: Pose::from_raw(g.pregrasp),
                closed: Pose::from_raw(g.closed),
                energy: g.energy,
                epsilon: g.epsilon,
                volume: g.volume,
                contacts: g.contacts,
                force_closure: g.force_closure != 0,
            });
        }
        Ok(plan)
    }

    /// The grasps, best first: force closure, then the larger epsilon.
    pub fn grasps(&self) -> &[PlannedGrasp] {
        &self.grasps
    }

    /// The closed DOF values of grasp `index`.
    pub fn grasp_dofs(&self, index: usize, dof_count: usize) -> Result<Vec<f64>> {
        let mut values = vec![0.0; dof_count];
        check(unsafe {
            sys::graspkit_plan_grasp_dofs(self.raw, index, values.as_mut_ptr(), values.len())
        })?;
        Ok(values)
    }

    /// A world with the hand closed as grasp `index` was measured: analysed or saved, it gives
    /// the same contacts, epsilon and volume.
    pub fn grasp_world(&self, index: usize) -> Result<World> {
        let mut raw = ptr::null_mut();
        check(unsafe { sys::graspkit_plan_grasp_world(self.raw, index, &mut raw) })?;
        Ok(World { raw })
    }
}
