//! Grasp datasets: one object's planned as `graspkit batch` plans it, read and written as HDF5.

use std::path::Path;
use std::ptr;

use graspkit_sys as sys;

use crate::error::{check, Result};
use crate::strings::c_path;
use crate::world::{raw_load_options, LoadOptions, Pose};

/// How to plan a dataset. `Default` is `graspkit batch`'s: 20 grasps, 40000 steps, seed 1.
#[derive(Clone, Debug, PartialEq)]
pub struct DatasetOptions {
    /// The best list's size.
    pub grasps: i32,
    /// The planner's budget in steps.
    pub steps: i64,
    /// The random seed.
    pub seed: u64,
    /// Label each grasp physically.
    pub validate: bool,
    /// Simulated seconds per validation direction.
    pub validate_seconds: f64,
}

impl Default for DatasetOptions {
    fn default() -> DatasetOptions {
        let mut raw = sys::graspkit_dataset_options::default();
        unsafe { sys::graspkit_dataset_options_default(&mut raw) };
        DatasetOptions {
            grasps: raw.grasps,
            steps: raw.steps,
            seed: raw.seed,
            validate: raw.validate != 0,
            validate_seconds: raw.validate_seconds,
        }
    }
}

/// One grasp of a dataset, in the object's frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DatasetGrasp {
    /// The hand, open.
    pub pregrasp: Pose,
    /// The hand, closed.
    pub grasp: Pose,
    /// L1 epsilon.
    pub epsilon: f64,
    /// L1 volume.
    pub volume: f64,
    /// Whether it is force closure.
    pub force_closure: bool,
    /// `Some(held)` once validated.
    pub held: Option<bool>,
    /// Contacts with the object.
    pub contacts: i32,
}

/// One object's grasp dataset (freed when dropped). `Send`, not `Sync`.
pub struct Dataset {
    raw: *mut sys::graspkit_dataset,
    grasps: Vec<DatasetGrasp>,
}

unsafe impl Send for Dataset {}

impl Drop for Dataset {
    fn drop(&mut self) {
        unsafe { sys::graspkit_dataset_free(self.raw) }
    }
}

impl Dataset {
    fn read(raw: *mut sys::graspkit_dataset) -> Result<Dataset> {
        let mut dataset = Dataset {
            raw,
            grasps: Vec::new(),
        };
        let mut count = 0usize;
        check(unsafe { sys::graspkit_dataset_count(raw, &mut count) })?;
        for i in 0..count {
            let mut g = sys::graspkit_dataset_grasp::default();
            check(unsafe { sys::graspkit_dataset_get_grasp(raw, i, &mut g) })?;
            dataset.grasps.push(DatasetGrasp {
                pregrasp: Pose::from_raw(g.pregrasp),
                grasp: Pose::from_raw(g.grasp),
                epsilon: g.epsilon,
                volume: g.volume,
                force_closure: g.force_closure != 0,
                held: if g.held < 0 { None } else { Some(g.held == 1) },
                contacts: g.contacts,
            });
        }
        Ok(dataset)
    }

    /// Plans the dataset of body file `object` with robot file `hand`.
    pub fn plan<P: AsRef<Path>, Q: AsRef<Path>>(
        hand: P,
        object: Q,
        load: &LoadOptions,
        options: &DatasetOptions,
    ) -> Result<Dataset> {
        let hand = c_path(hand.as_ref())?;
        let object = c_path(object.as_ref())?;
        let load = raw_load_options(load)?;
        let raw_options = sys::graspkit_dataset_options {
            grasps: options.grasps,
            steps: options.steps,
            seed: options.seed,
            validate: options.validate as i32,
            validate_seconds: options.validate_seconds,
        };
        let mut raw = ptr::null_mut();
        check(unsafe {
            sys::graspkit_dataset_plan(
                hand.as_ptr(),
                object.as_ptr(),
                &load.raw,
                &raw_options,
                &mut raw,
            )
        })?;
        Dataset::read(raw)
    }

    /// Reads a dataset file.
    pub fn load<P: AsRef<Path>>(path: P) -> Result<Dataset> {
        let path = c_path(path.as_ref())?;
        let mut raw = ptr::null_mut();
        check(unsafe { sys::graspkit_dataset_load(path.as_ptr(), &mut raw) })?;
        Dataset::read(raw)
    }

    /// Writes the dataset, atomically.
    pub fn save<P: AsRef<Path>>(&self, path: P) -> Result<()> {
        let path = c_path(path.as_ref())?;
        check(unsafe { sys::graspkit_dataset_save(self.raw, path.as_ptr()) })
    }

    /// The grasps, best first.
    pub fn grasps(&self) -> &[DatasetGrasp] {
        &self.grasps
    }
}
