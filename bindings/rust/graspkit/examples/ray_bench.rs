//! The Rust layer's cost on a batch of rays: 1e6 rays at the mug of GraspIt!'s plannerMug (the
//! mug alone in the scene, the C ABI bench's set: from a sphere of radius 200 mm about the mug
//! towards random points of its bounding box), cast through the safe `intersect_into` and
//! through the raw `graspkit_ray_scene_intersect`, alternately in the same loop.
//!   cargo run --release --example ray_bench -- [WORLD]
//! Prints rays/s of both and `x_sys`, the raw call's time divided by the safe one's (1 is
//! parity). bench/c_abi_bench measures the C ABI against the C++ call the same way.

use std::time::Instant;

use graspkit::{LoadOptions, RawHit, Ray, RayScene, World};

/// A small deterministic generator (xorshift), so the bench needs no crate.
struct Random(u64);
impl Random {
    fn unit(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn main() {
    let world_file = std::env::args().nth(1).unwrap_or_else(|| {
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../../../shared/graspit-data/worlds/plannerMug.xml"
        )
        .to_string()
    });
    let world = World::load(&world_file, &LoadOptions::default()).expect("the world loads");
    let scene = RayScene::new(&world, false).expect("a scene");
    // A box of +-60 mm about the mug's origin: the mug is about 90 mm across, so most rays hit.
    let centre = world.body_pose(0).unwrap().translation;
    let (lo, hi) = (
        [centre[0] - 60.0, centre[1] - 60.0, centre[2] - 60.0],
        [centre[0] + 60.0, centre[1] + 60.0, centre[2] + 60.0],
    );
    let mut random = Random(7);
    let count = 1_000_000;
    let rays: Vec<Ray> = (0..count)
        .map(|_| {
            let mut d = [0.0; 3];
            for v in d.iter_mut() {
                *v = random.unit() - 0.5;
            }
            let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(1e-9);
            let from = [
                centre[0] + 200.0 * d[0] / n,
                centre[1] + 200.0 * d[1] / n,
                centre[2] + 200.0 * d[2] / n,
            ];
            let mut to = [0.0; 3];
            for k in 0..3 {
                to[k] = lo[k] + random.unit() * (hi[k] - lo[k]);
            }
            graspkit::ray(from, [to[0] - from[0], to[1] - from[1], to[2] - from[2]])
        })
        .collect();
    let mut hits = vec![RawHit::default(); count];
    let (mut safe, mut raw) = (0.0, 0.0);
    let rounds = 10;
    for _ in 0..rounds {
        let start = Instant::now();
        scene.intersect_into(&rays, &mut hits).unwrap();
        safe += start.elapsed().as_secs_f64();
        let start = Instant::now();
        let status = unsafe {
            graspkit_sys::graspkit_ray_scene_intersect(
                scene_raw(&scene),
                rays.as_ptr(),
                hits.as_mut_ptr(),
                rays.len(),
            )
        };
        assert_eq!(status, graspkit_sys::GRASPKIT_OK);
        raw += start.elapsed().as_secs_f64();
    }
    let n = (count * rounds) as f64;
    let hit_count = hits.iter().filter(|h| h.hit != 0).count();
    println!(
        "rays {} (hits {}), safe {:.3} M rays/s, raw {:.3} M rays/s, x_sys {:.3}",
        count,
        hit_count,
        n / safe / 1e6,
        n / raw / 1e6,
        raw / safe
    );
}

/// The scene's C handle, for the raw call.
fn scene_raw(scene: &RayScene) -> *const graspkit_sys::graspkit_ray_scene {
    scene.as_raw()
}
