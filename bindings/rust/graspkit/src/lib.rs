//! graspkit from Rust: a grasp simulator that reads GraspIt!'s files, over its C ABI
//! (`bindings/c/include/graspkit.h`).
//!
//! ```no_run
//! let mut world = graspkit::World::load("plannerMug.xml", &graspkit::LoadOptions::default())?;
//! let hand = world.first_hand()?;
//! let mug = world.find_body("mug")?;
//! world.autograsp(hand)?;
//! let grasp = world.analyze_grasp(hand, mug, graspkit::WrenchSpace::L1)?;
//! println!("{} contacts, volume {}", grasp.contacts()?.len(), grasp.quality()?.volume);
//! # Ok::<(), graspkit::Error>(())
//! ```
//!
//! Every call returns [`Result`]; an [`Error`] carries the C ABI's status and the file, line
//! and element of the input at fault. Handles ([`World`], [`Grasp`], [`RayScene`], [`Plan`])
//! are freed when dropped. They are `Send` but not `Sync`: move one to another thread, but give
//! each thread its own (clone worlds with [`World::try_clone`]; clones share the meshes):
//!
//! ```compile_fail
//! fn shared<T: Sync>() {}
//! shared::<graspkit::World>();
//! ```
//!
//! Units are GraspIt!'s: millimetres, radians (mm for prismatic DOFs), grams.

mod dataset;
mod dynamics;
mod error;
mod grasp;
mod plan;
mod rays;
mod script;
mod strings;
mod views;
mod world;

pub use dataset::{Dataset, DatasetGrasp, DatasetOptions};
pub use dynamics::{
    generate_object, DirectionResult, RenderOptions, Simulation, SimulationOptions, StepReport,
    Validation,
};
pub use error::{Error, Result, Status};
pub use grasp::{Contact, ContactModel, Grasp, Quality, WrenchSpace};
pub use plan::{Plan, PlanOptions, PlannedGrasp};
pub use rays::{ray, RawHit, Ray, RayHit, RayScene};
pub use script::{
    plugin_load, plugin_search_path, plugins_scan, run_script, set_log_callback, LogRecord,
    PluginInfo, ScriptOptions,
};
pub use views::{Body, Robot};
pub use world::{AutoGrasp, BodyRef, LoadOptions, MotionEnd, Pose, World};

/// The engine's version, e.g. "0.1.0".
pub fn version() -> String {
    error::text(unsafe { graspkit_sys::graspkit_version() })
}

/// Whether the loaded library speaks the ABI this crate was written for.
pub fn abi_matches() -> bool {
    unsafe { graspkit_sys::graspkit_abi_version() == graspkit_sys::GRASPKIT_ABI_VERSION }
}
