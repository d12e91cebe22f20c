//! Dynamics, validation, pictures and generated objects: the host layer's defaults, read from
//! the C ABI (`graspkit_*_options_default`), so that they are graspkit's everywhere.

use std::path::{Path, PathBuf};
use std::ptr;

use graspkit_sys as sys;

use crate::error::{check, Result};
use crate::strings::{c_path, c_string, read_string};
use crate::world::World;

/// One step's report.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StepReport {
    /// The world's time after the step, s.
    pub time: f64,
    /// Contacts that entered the impulse problem.
    pub contacts: i32,
    /// Those that pushed.
    pub active_contacts: i32,
    /// Joint-limit constraints.
    pub joint_limits: i32,
}

impl StepReport {
    fn from_raw(r: sys::graspkit_step_report) -> StepReport {
        StepReport {
            time: r.time,
            contacts: r.contacts,
            active_contacts: r.active_contacts,
            joint_limits: r.joint_limits,
        }
    }
}

/// How to simulate. `Default` is `graspkit simulate`'s: 1 s at dt 0.0025, the world's gravity.
#[derive(Clone, Debug, PartialEq)]
pub struct SimulationOptions {
    /// Simulated time, s.
    pub seconds: f64,
    /// Time step, s.
    pub dt: f64,
    /// Gravity in mm/s^2 (`None`: the world's own).
    pub gravity: Option<[f64; 3]>,
    /// Drive the first hand's DOFs towards their closing limits.
    pub autograsp: bool,
}

impl Default for SimulationOptions {
    fn default() -> SimulationOptions {
        let mut raw = std::mem::MaybeUninit::<sys::graspkit_simulation_options>::zeroed();
        // Cannot fail for a valid pointer.
        unsafe { sys::graspkit_simulation_options_default(raw.as_mut_ptr()) };
        let raw = unsafe { raw.assume_init() };
        SimulationOptions {
            seconds: raw.seconds,
            dt: raw.dt,
            gravity: None,
            autograsp: raw.autograsp != 0,
        }
    }
}

/// How a simulation ended.
#[derive(Clone, Debug, PartialEq)]
pub struct Simulation {
    /// False when it stopped on a bad state; `stop_reason` says which.
    pub completed: bool,
    /// "completed", or why it stopped.
    pub stop_reason: String,
    /// Steps taken.
    pub steps: i32,
    /// The world's time at the end, s.
    pub time: f64,
    /// The last step's report.
    pub last: StepReport,
}

/// One validation direction's result.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionResult {
    /// Unit, world frame: +x, -x, +y, -y, +z, -z in turn.
    pub direction: [f64; 3],
    /// Whether the hand held the object's weight this way.
    pub held: bool,
    /// The object's largest travel relative to the palm, mm.
    pub slip: f64,
    /// Its largest rotation relative to the palm, rad.
    pub turn: f64,
    /// Simulated seconds.
    pub seconds: f64,
}

/// A grasp's physical label, as `graspkit validate` gives it.
#[derive(Clone, Debug, PartialEq)]
pub struct Validation {
    /// Every direction held.
    pub held: bool,
    /// How many held.
    pub directions_held: i32,
    /// +x, -x, +y, -y, +z, -z.
    pub directions: Vec<DirectionResult>,
    /// Simulated seconds of the squeeze before the pulls.
    pub settle_seconds: f64,
}

/// A picture's settings. `Default` is `graspkit render`'s: 640 x 480, auto camera.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderOptions {
    /// Pixels.
    pub width: i32,
    /// Pixels.
    pub height: i32,
    /// auto, world, iso, +x, -x, +y, -y, +z, -z.
    pub camera: String,
    /// Mark the first hand's contacts with the first graspable body.
    pub contacts: bool,
    /// Samples per pixel along each axis, 1..4.
    pub samples: i32,
}

impl Default for RenderOptions {
    fn default() -> RenderOptions {
        let mut raw = std::mem::MaybeUninit::<sys::graspkit_render_options>::zeroed();
        unsafe { sys::graspkit_render_options_default(raw.as_mut_ptr()) };
        let raw = unsafe { raw.assume_init() };
        RenderOptions {
            width: raw.width,
            height: raw.height,
            camera: crate::error::text(raw.camera),
            contacts: raw.contacts != 0,
            samples: raw.samples,
        }
    }
}

impl World {
    /// Removes free body `body`; later bodies move down one index.
    pub fn remove_body(&mut self, body: i32) -> Result<()> {
        check(unsafe { sys::graspkit_world_remove_body(self.raw, body) })
    }

    /// Advances the dynamics by `dt` seconds (0: the default step).
    pub fn step(&mut self, dt: f64) -> Result<StepReport> {
        let mut report = sys::graspkit_step_report::default();
        check(unsafe { sys::graspkit_world_step(self.raw, dt, &mut report) })?;
        Ok(StepReport::from_raw(report))
    }

    /// Steps the world as `graspkit simulate` does. A simulation that blows up is not an
    /// error: `completed` is false and `stop_reason` says why.
    pub fn simulate(&mut self, options: &SimulationOptions) -> Result<Simulation> {
        let mut raw = std::mem::MaybeUninit::<sys::graspkit_simulation_options>::zeroed();
        check(unsafe { sys::graspkit_simulation_options_default(raw.as_mut_ptr()) })?;
        let mut raw = unsafe { raw.assume_init() };
        raw.seconds = options.seconds;
        raw.dt = options.dt;
        raw.autograsp = options.autograsp as i32;
        if let Some(g) = options.gravity {
            raw.use_gravity = 1;
            raw.gravity = g;
        }
        let mut result = sys::graspkit_simulation_result::default();
        check(unsafe { sys::graspkit_world_simulate(self.raw, &raw, &mut result) })?;
        let completed = result.completed != 0;
        Ok(Simulation {
            completed,
            stop_reason: if completed {
                "completed".to_string()
            } else {
                crate::error::text(unsafe { sys::graspkit_last_error() })
            },
            steps: result.steps,
            time: result.time,
            last: StepReport::from_raw(result.last),
        })
    }

    /// Labels the grasp the world holds (its first hand closed on its first graspable body) as
    /// `graspkit validate` does; `seconds` per direction (0: the default, 2).
    pub fn validate(&self, seconds: f64) -> Result<Validation> {
        let mut raw = sys::graspkit_validation::default();
        check(unsafe { sys::graspkit_validate(self.raw, seconds, &mut raw) })?;
        Ok(Validation {
            held: raw.held != 0,
            directions_held: raw.directions_held,
            settle_seconds: raw.settle_seconds,
            directions: raw
                .directions
                .iter()
                .map(|d| DirectionResult {
                    direction: d.direction,
                    held: d.held != 0,
                    slip: d.slip,
                    turn: d.turn,
                    seconds: d.seconds,
                })
                .collect(),
        })
    }

    /// Draws the world as `graspkit render` does: height rows of width RGB pixels, top row
    /// first. With `png`, also writes it there.
    pub fn render(&self, options: &RenderOptions, png: Option<&Path>) -> Result<Vec<u8>> {
        let camera = c_string(&options.camera)?;
        let raw = sys::graspkit_render_options {
            width: options.width,
            height: options.height,
            camera: camera.as_ptr(),
            contacts: options.contacts as i32,
            samples: options.samples,
        };
        let size = options.width.max(0) as usize * options.height.max(0) as usize * 3;
        let mut rgb = vec![0u8; size];
        let png = png.map(c_path).transpose()?;
        check(unsafe {
            sys::graspkit_world_render(
                self.raw,
                &raw,
                rgb.as_mut_ptr(),
                rgb.len(),
                png.as_ref().map_or(ptr::null(), |p| p.as_ptr()),
            )
        })?;
        Ok(rgb)
    }
}

/// Writes object `index` of the generated set `seed` into `folder` as `graspkit objects` does
/// (NAME.off and NAME.xml); returns the Body XML's path.
pub fn generate_object<P: AsRef<Path>>(folder: P, seed: u64, index: usize) -> Result<PathBuf> {
    let folder = c_path(folder.as_ref())?;
    let path = read_string(|buffer, capacity, length| unsafe {
        sys::graspkit_generate_object(folder.as_ptr(), seed, index, buffer, capacity, length)
    })?;
    Ok(PathBuf::from(path))
}
