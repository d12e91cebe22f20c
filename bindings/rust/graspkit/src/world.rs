//! Worlds: bodies, robots, autograsp and grasp analysis.

use std::os::raw::c_int;
use std::path::{Path, PathBuf};
use std::ptr;

use graspkit_sys as sys;

use crate::error::{check, Result};
use crate::grasp::{Grasp, WrenchSpace};
use crate::strings::{c_path, c_string, read_string, CStrings};

/// A frame in the world: translation in mm and a unit quaternion (w, x, y, z).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// mm.
    pub translation: [f64; 3],
    /// Unit quaternion, w first.
    pub rotation: [f64; 4],
}

impl Pose {
    /// The identity: at the origin, not turned.
    pub const IDENTITY: Pose = Pose {
        translation: [0.0; 3],
        rotation: [1.0, 0.0, 0.0, 0.0],
    };
    pub(crate) fn to_raw(self) -> sys::graspkit_pose {
        sys::graspkit_pose {
            translation: self.translation,
            rotation: self.rotation,
        }
    }
    pub(crate) fn from_raw(raw: sys::graspkit_pose) -> Pose {
        Pose {
            translation: raw.translation,
            rotation: raw.rotation,
        }
    }
}

/// Any solid a ray can hit or a contact can touch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BodyRef {
    /// A free body, by its index.
    Body(i32),
    /// Link `link` of chain `chain` of robot `robot`; chain = link = -1 is the palm.
    Link { robot: i32, chain: i32, link: i32 },
    /// The mount piece of connection `connection`.
    Mount(i32),
}

impl BodyRef {
    pub(crate) fn from_raw(raw: sys::graspkit_body_ref) -> BodyRef {
        match raw.kind {
            sys::GRASPKIT_LINK => BodyRef::Link {
                robot: raw.index,
                chain: raw.chain,
                link: raw.link,
            },
            sys::GRASPKIT_MOUNT => BodyRef::Mount(raw.index),
            _ => BodyRef::Body(raw.index),
        }
    }
    pub(crate) fn to_raw(self) -> sys::graspkit_body_ref {
        match self {
            BodyRef::Body(index) => sys::graspkit_body_ref {
                kind: sys::GRASPKIT_BODY,
                index,
                chain: -1,
                link: -1,
            },
            BodyRef::Link { robot, chain, link } => sys::graspkit_body_ref {
                kind: sys::GRASPKIT_LINK,
                index: robot,
                chain,
                link,
            },
            BodyRef::Mount(index) => sys::graspkit_body_ref {
                kind: sys::GRASPKIT_MOUNT,
                index,
                chain: -1,
                link: -1,
            },
        }
    }
}

/// How a load finds a world's files.
#[derive(Clone, Debug, Default)]
pub struct LoadOptions {
    /// Folders searched first for a world's `<filename>`s (graspkit's `--root`).
    pub roots: Vec<PathBuf>,
    /// A robot of an unknown type loads as a generic hand instead of failing.
    pub generic_robots: bool,
    /// URDF: folders holding the packages `package://` paths name (`--package-path`).
    pub package_paths: Vec<PathBuf>,
    /// URDF: the link taken as the palm (`--palm`; the root link when `None`).
    pub palm: Option<String>,
    /// URDF: every link's material (`--urdf-material`; rubber when `None`).
    pub urdf_material: Option<String>,
    /// URDF: the SRDF whose `<disable_collisions>` pairs are never checked (`--srdf`).
    pub srdf: Option<PathBuf>,
    /// The way DOF i closes the hand (`--close`): +1 towards its upper limit, -1 its lower,
    /// 0 as the file or the inferred direction says.
    pub closing: Vec<i32>,
}

impl LoadOptions {
    /// Options with one root folder.
    pub fn with_root<P: AsRef<Path>>(root: P) -> LoadOptions {
        LoadOptions {
            roots: vec![root.as_ref().to_path_buf()],
            ..LoadOptions::default()
        }
    }
}

/// How autograsp ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MotionEnd {
    /// Nothing moves any more.
    Settled,
    /// A contact appeared (stop at contact).
    Contact,
    /// GraspIt!'s failsafe ended it.
    IterationLimit,
    /// The contact instant could not be bracketed.
    InterpolationError,
    /// An approach went its whole distance without touching.
    NoContact,
}

/// What closing the hand did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AutoGrasp {
    /// How it ended.
    pub end: MotionEnd,
    /// Steps taken.
    pub steps: i32,
}

/// A world: bodies, robots and their poses. Loading and cloning are the only ways to make one;
/// it is freed when dropped.
///
/// Threads: a `World` is `Send` (move it to another thread) but not `Sync` (the C ABI allows
/// one thread at a time per handle); give each thread its own [`World::try_clone`], which shares
/// the meshes and is cheap.
pub struct World {
    pub(crate) raw: *mut sys::graspkit_world,
}

// The C ABI lets a handle move between threads; it must not be used by two at once (no Sync).
unsafe impl Send for World {}

impl Drop for World {
    fn drop(&mut self) {
        unsafe { sys::graspkit_world_free(self.raw) }
    }
}

pub(crate) struct RawLoadOptions {
    _roots: CStrings,
    _packages: CStrings,
    _texts: Vec<Option<std::ffi::CString>>,
    _closing: Vec<i32>,
    pub(crate) raw: sys::graspkit_load_options,
}

fn optional_c(text: Option<&str>) -> Result<Option<std::ffi::CString>> {
    text.map(crate::strings::c_string).transpose()
}

fn pointer(text: &Option<std::ffi::CString>) -> *const std::os::raw::c_char {
    text.as_ref().map_or(ptr::null(), |t| t.as_ptr())
}

pub(crate) fn raw_load_options(options: &LoadOptions) -> Result<RawLoadOptions> {
    let roots = CStrings::from_paths(&options.roots)?;
    let packages = CStrings::from_paths(&options.package_paths)?;
    let srdf = match &options.srdf {
        Some(path) => Some(c_path(path)?),
        None => None,
    };
    let texts = vec![
        optional_c(options.palm.as_deref())?,
        optional_c(options.urdf_material.as_deref())?,
        srdf,
    ];
    let closing = options.closing.clone();
    let raw = sys::graspkit_load_options {
        roots: roots.as_ptr(),
        root_count: roots.len(),
        generic_robots: options.generic_robots as c_int,
        package_paths: packages.as_ptr(),
        package_path_count: packages.len(),
        palm: pointer(&texts[0]),
        urdf_material: pointer(&texts[1]),
        srdf: pointer(&texts[2]),
        closing: closing.as_ptr(),
        close_count: closing.len(),
    };
    Ok(RawLoadOptions {
        _roots: roots,
        _packages: packages,
        _texts: texts,
        _closing: closing,
        raw,
    })
}

impl World {
    /// An empty world.
    pub fn new() -> Result<World> {
        let mut raw = ptr::null_mut();
        check(unsafe { sys::graspkit_world_new(&mut raw) })?;
        Ok(World { raw })
    }

    /// Loads a World, Robot or Body XML file.
    pub fn load<P: AsRef<Path>>(path: P, options: &LoadOptions) -> Result<World> {
        let path = c_path(path.as_ref())?;
        let options = raw_load_options(options)?;
        let mut raw = ptr::null_mut();
        check(unsafe { sys::graspkit_world_load(path.as_ptr(), &options.raw, &mut raw) })?;
        Ok(World { raw })
    }

    /// A copy sharing the meshes.
    pub fn try_clone(&self) -> Result<World> {
        let mut raw = ptr::null_mut();
        check(unsafe { sys::graspkit_world_clone(self.raw, &mut raw) })?;
        Ok(World { raw })
    }

    /// Saves as GraspIt! writes world files, atomically.
    pub fn save<P: AsRef<Path>>(&self, path: P) -> Result<()> {
        let path = c_path(path.as_ref())?;
        check(unsafe { sys::graspkit_world_save(self.raw, path.as_ptr()) })
    }

    /// Adds the bodies and robots of a file; returns the index of the first body and of the
    /// first robot added. On failure the world is left as it was.
    pub fn add_file<P: AsRef<Path>>(
        &mut self,
        path: P,
        options: &LoadOptions,
    ) -> Result<(i32, i32)> {
        let path = c_path(path.as_ref())?;
        let options = raw_load_options(options)?;
        let (mut body, mut robot) = (0, 0);
        check(unsafe {
            sys::graspkit_world_add_file(
                self.raw,
                path.as_ptr(),
                &options.raw,
                &mut body,
                &mut robot,
            )
        })?;
        Ok((body, robot))
    }

    /// How many free bodies (obstacles and graspable bodies) the world has.
    pub fn body_count(&self) -> Result<i32> {
        let mut count = 0;
        check(unsafe { sys::graspkit_world_body_count(self.raw, &mut count) })?;
        Ok(count)
    }

    /// The index of the body named `name`.
    pub fn find_body(&self, name: &str) -> Result<i32> {
        let name = c_string(name)?;
        let mut body = 0;
        check(unsafe { sys::graspkit_world_find_body(self.raw, name.as_ptr(), &mut body) })?;
        Ok(body)
    }

    /// Body `body`'s name.
    pub fn body_name(&self, body: i32) -> Result<String> {
        read_string(|b, c, l| unsafe { sys::graspkit_body_name(self.raw, body, b, c, l) })
    }

    /// Whether body `body` is graspable (dynamic) rather than an obstacle.
    pub fn is_graspable(&self, body: i32) -> Result<bool> {
        let mut graspable = 0;
        check(unsafe { sys::graspkit_body_is_graspable(self.raw, body, &mut graspable) })?;
        Ok(graspable != 0)
    }

    /// Body `body`'s mass (g) and centre of gravity in its own frame (mm).
    pub fn mass(&self, body: i32) -> Result<(f64, [f64; 3])> {
        let mut mass = 0.0;
        let mut cog = [0.0; 3];
        check(unsafe { sys::graspkit_body_mass(self.raw, body, &mut mass, cog.as_mut_ptr()) })?;
        Ok((mass, cog))
    }

    /// Body `body`'s pose.
    pub fn body_pose(&self, body: i32) -> Result<Pose> {
        let mut pose = sys::graspkit_pose::default();
        check(unsafe { sys::graspkit_body_get_pose(self.raw, body, &mut pose) })?;
        Ok(Pose::from_raw(pose))
    }

    /// Moves body `body` (the quaternion is normalised; a zero or non-finite one is refused).
    pub fn set_body_pose(&mut self, body: i32, pose: &Pose) -> Result<()> {
        check(unsafe { sys::graspkit_body_set_pose(self.raw, body, &pose.to_raw()) })
    }

    /// The name of any solid.
    pub fn name_of(&self, body: BodyRef) -> Result<String> {
        let raw = body.to_raw();
        read_string(|b, c, l| unsafe { sys::graspkit_body_ref_name(self.raw, &raw, b, c, l) })
    }

    /// How many robots the world has.
    pub fn robot_count(&self) -> Result<i32> {
        let mut count = 0;
        check(unsafe { sys::graspkit_world_robot_count(self.raw, &mut count) })?;
        Ok(count)
    }

    /// The index of the robot named `name`.
    pub fn find_robot(&self, name: &str) -> Result<i32> {
        let name = c_string(name)?;
        let mut robot = 0;
        check(unsafe { sys::graspkit_world_find_robot(self.raw, name.as_ptr(), &mut robot) })?;
        Ok(robot)
    }

    /// The world's first robot that is a hand (GraspIt!'s current hand).
    pub fn first_hand(&self) -> Result<i32> {
        let mut robot = 0;
        check(unsafe { sys::graspkit_world_first_hand(self.raw, &mut robot) })?;
        Ok(robot)
    }

    /// Robot `robot`'s name.
    pub fn robot_name(&self, robot: i32) -> Result<String> {
        read_string(|b, c, l| unsafe { sys::graspkit_robot_name(self.raw, robot, b, c, l) })
    }

    /// How many DOFs robot `robot` has.
    pub fn dof_count(&self, robot: i32) -> Result<usize> {
        let mut count = 0;
        check(unsafe { sys::graspkit_robot_dof_count(self.raw, robot, &mut count) })?;
        Ok(count as usize)
    }

    /// Robot `robot`'s DOF values (radians, mm for prismatic DOFs).
    pub fn dofs(&self, robot: i32) -> Result<Vec<f64>> {
        let mut values = vec![0.0; self.dof_count(robot)?];
        check(unsafe {
            sys::graspkit_robot_get_dofs(self.raw, robot, values.as_mut_ptr(), values.len())
        })?;
        Ok(values)
    }

    /// Sets every DOF of robot `robot` (clamped into range); `values` must hold one per DOF.
    pub fn set_dofs(&mut self, robot: i32, values: &[f64]) -> Result<()> {
        check(unsafe {
            sys::graspkit_robot_set_dofs(self.raw, robot, values.as_ptr(), values.len())
        })
    }

    /// Robot `robot`'s DOF ranges: (min, max) per DOF.
    pub fn dof_limits(&self, robot: i32) -> Result<(Vec<f64>, Vec<f64>)> {
        let n = self.dof_count(robot)?;
        let (mut min, mut max) = (vec![0.0; n], vec![0.0; n]);
        check(unsafe {
            sys::graspkit_robot_dof_limits(self.raw, robot, min.as_mut_ptr(), max.as_mut_ptr(), n)
        })?;
        Ok((min, max))
    }

    /// Robot `robot`'s base (palm) pose.
    pub fn robot_pose(&self, robot: i32) -> Result<Pose> {
        let mut pose = sys::graspkit_pose::default();
        check(unsafe { sys::graspkit_robot_get_pose(self.raw, robot, &mut pose) })?;
        Ok(Pose::from_raw(pose))
    }

    /// Moves robot `robot` (and every robot mounted on it).
    pub fn set_robot_pose(&mut self, robot: i32, pose: &Pose) -> Result<()> {
        check(unsafe { sys::graspkit_robot_set_pose(self.raw, robot, &pose.to_raw()) })
    }

    /// How many kinematic chains robot `robot` has.
    pub fn chain_count(&self, robot: i32) -> Result<i32> {
        let mut count = 0;
        check(unsafe { sys::graspkit_robot_chain_count(self.raw, robot, &mut count) })?;
        Ok(count)
    }

    /// How many links chain `chain` of robot `robot` has.
    pub fn link_count(&self, robot: i32, chain: i32) -> Result<i32> {
        let mut count = 0;
        check(unsafe { sys::graspkit_robot_link_count(self.raw, robot, chain, &mut count) })?;
        Ok(count)
    }

    /// The world pose of a link (chain = link = -1: the palm).
    pub fn link_pose(&self, robot: i32, chain: i32, link: i32) -> Result<Pose> {
        let mut pose = sys::graspkit_pose::default();
        check(unsafe { sys::graspkit_robot_link_pose(self.raw, robot, chain, link, &mut pose) })?;
        Ok(Pose::from_raw(pose))
    }

    /// Closes hand `robot` as its robot type closes (GraspIt!'s autograsp).
    pub fn autograsp(&mut self, robot: i32) -> Result<AutoGrasp> {
        let mut result = sys::graspkit_autograsp_result::default();
        check(unsafe { sys::graspkit_robot_autograsp(self.raw, robot, &mut result) })?;
        let end = match result.end {
            sys::GRASPKIT_MOTION_SETTLED => MotionEnd::Settled,
            sys::GRASPKIT_MOTION_CONTACT => MotionEnd::Contact,
            sys::GRASPKIT_MOTION_ITERATION_LIMIT => MotionEnd::IterationLimit,
            sys::GRASPKIT_MOTION_INTERPOLATION_ERROR => MotionEnd::InterpolationError,
            _ => MotionEnd::NoContact,
        };
        Ok(AutoGrasp {
            end,
            steps: result.steps,
        })
    }

    /// Hand `robot`'s contacts with body `object` as the world stands, and their quality.
    pub fn analyze_grasp(&self, robot: i32, object: i32, space: WrenchSpace) -> Result<Grasp> {
        let mut raw = ptr::null_mut();
        let space = match space {
            WrenchSpace::L1 => sys::GRASPKIT_GWS_L1,
            WrenchSpace::LInfinity => sys::GRASPKIT_GWS_LINF,
        };
        check(unsafe { sys::graspkit_grasp_analyze(self.raw, robot, object, space, &mut raw) })?;
        Ok(Grasp { raw })
    }
}
