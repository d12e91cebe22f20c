//! Rays and nearest surface points, in batches, over a world's Embree scene.

use std::ptr;

use graspkit_sys as sys;

use crate::error::{check, Result};
use crate::world::{BodyRef, World};

/// A ray, as the C ABI takes it: origin (mm), direction (any non-zero length), and the segment
/// [tmin, tmax] along the normalised direction (mm; `f64::INFINITY` for no end).
pub use sys::graspkit_ray as Ray;
/// A hit, as the C ABI writes it (`hit == 0`: nothing was met); see [`RayScene::intersect_into`].
pub use sys::graspkit_ray_hit as RawHit;

/// Where a ray (or a nearest-point query) met a surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayHit {
    /// The solid met.
    pub body: BodyRef,
    /// The triangle of its mesh.
    pub triangle: i32,
    /// World, mm.
    pub point: [f64; 3],
    /// The triangle's counter-clockwise normal, unit.
    pub normal: [f64; 3],
    /// mm from the ray's origin (or the query point).
    pub distance: f64,
}

impl RayHit {
    fn from_raw(raw: &RawHit) -> Option<RayHit> {
        if raw.hit == 0 {
            return None;
        }
        Some(RayHit {
            body: BodyRef::from_raw(raw.body),
            triangle: raw.triangle,
            point: raw.point,
            normal: raw.normal,
            distance: raw.distance,
        })
    }
}

/// A ray from `origin` along `direction`, unbounded.
pub fn ray(origin: [f64; 3], direction: [f64; 3]) -> Ray {
    Ray {
        origin,
        direction,
        tmin: 0.0,
        tmax: f64::INFINITY,
    }
}

/// A world's solids for ray queries (freed when dropped). Build it once and query it many
/// times; after the world moved, [`RayScene::update`]. `Send`, not `Sync`.
pub struct RayScene {
    raw: *mut sys::graspkit_ray_scene,
}

unsafe impl Send for RayScene {}

impl Drop for RayScene {
    fn drop(&mut self) {
        unsafe { sys::graspkit_ray_scene_free(self.raw) }
    }
}

impl RayScene {
    /// A scene of `world`'s solids; `include_links = false` leaves the robots' links out.
    pub fn new(world: &World, include_links: bool) -> Result<RayScene> {
        let mut raw = ptr::null_mut();
        check(unsafe { sys::graspkit_ray_scene_new(world.raw, include_links as i32, &mut raw) })?;
        Ok(RayScene { raw })
    }

    /// The C handle, for calls of `graspkit-sys` (it stays owned by the scene).
    pub fn as_raw(&self) -> *const sys::graspkit_ray_scene {
        self.raw
    }

    /// Re-reads the poses from `world` (the world the scene was built from, or a clone).
    pub fn update(&mut self, world: &World) -> Result<()> {
        check(unsafe { sys::graspkit_ray_scene_update(self.raw, world.raw) })
    }

    /// The first surface each ray meets. A bad ray (NaN, zero direction, tmin < 0) fails the
    /// whole batch before any ray is traced.
    pub fn intersect(&self, rays: &[Ray]) -> Result<Vec<Option<RayHit>>> {
        let mut hits = vec![RawHit::default(); rays.len()];
        self.intersect_into(rays, &mut hits)?;
        Ok(hits.iter().map(RayHit::from_raw).collect())
    }

    /// The same into a buffer of the caller's, with no allocation (`hits.len()` must equal
    /// `rays.len()`): what a loop over millions of rays should use.
    pub fn intersect_into(&self, rays: &[Ray], hits: &mut [RawHit]) -> Result<()> {
        if hits.len() != rays.len() {
            return Err(crate::error::invalid_pub(&format!(
                "{} rays but {} hit slots",
                rays.len(),
                hits.len()
            )));
        }
        check(unsafe {
            sys::graspkit_ray_scene_intersect(
                self.raw,
                rays.as_ptr(),
                hits.as_mut_ptr(),
                rays.len(),
            )
        })
    }

    /// For each point (mm), the nearest surface point within `max_distance` (mm;
    /// `f64::INFINITY` for any), or None.
    pub fn nearest(&self, points: &[[f64; 3]], max_distance: f64) -> Result<Vec<Option<RayHit>>> {
        let mut hits = vec![RawHit::default(); points.len()];
        check(unsafe {
            sys::graspkit_ray_scene_nearest(
                self.raw,
                points.as_ptr() as *const f64,
                points.len(),
                max_distance,
                hits.as_mut_ptr(),
            )
        })?;
        Ok(hits.iter().map(RayHit::from_raw).collect())
    }
}
