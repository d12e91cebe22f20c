//! The crate against independent truth: GraspIt!'s figures for plannerMug
//! (`../shared/reference/graspit-figures.json`: 6 contacts, epsilon -1, volume 0.00392128283545,
//! DOFs after autograsp [0, 1.024375, 1.024375, 1.121875]), the closed forms of the project's
//! box (60 x 60 x 120 mm about its origin), and the error paths.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

use graspkit::{
    BodyRef, LoadOptions, Plan, PlanOptions, Pose, RayScene, Status, World, WrenchSpace,
};

fn project() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../..")
}

/// `../shared` beside the project, or $GRASPKIT_SHARED; None (said loudly) when absent.
fn shared() -> Option<PathBuf> {
    let dir = match std::env::var_os("GRASPKIT_SHARED") {
        Some(d) if !d.is_empty() => PathBuf::from(d),
        _ => project().join("../shared"),
    };
    if dir.join("graspit-data").is_dir() {
        Some(dir)
    } else {
        eprintln!("SKIPPED: ../shared not found (set GRASPKIT_SHARED)");
        None
    }
}

fn planner_mug() -> Option<(World, PathBuf)> {
    let shared = shared()?;
    let data = shared.join("graspit-data");
    let world = World::load(data.join("worlds/plannerMug.xml"), &LoadOptions::default()).unwrap();
    Some((world, data))
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("graspkit-rust-{}-{}", std::process::id(), name));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn box_world() -> World {
    World::load(
        project().join("models/objects/box.xml"),
        &LoadOptions::default(),
    )
    .unwrap()
}

#[test]
fn the_library_speaks_this_crates_abi() {
    assert!(graspkit::abi_matches());
    assert!(!graspkit::version().is_empty());
}

#[test]
fn autograsp_on_planner_mug_gives_graspits_figures() {
    let (mut world, _) = match planner_mug() {
        Some(w) => w,
        None => return,
    };
    let hand = world.first_hand().unwrap();
    assert_eq!(world.robot_name(hand).unwrap(), "Barrett");
    let mug = world.find_body("mug").unwrap();
    assert!(world.is_graspable(mug).unwrap());
    let closed = world.autograsp(hand).unwrap();
    assert_eq!(closed.end, graspkit::MotionEnd::Settled);
    let dofs = world.dofs(hand).unwrap();
    for (got, want) in dofs.iter().zip([0.0, 1.024375, 1.024375, 1.121875]) {
        assert!((got - want).abs() < 1e-3, "{:?}", dofs);
    }
    let grasp = world.analyze_grasp(hand, mug, WrenchSpace::L1).unwrap();
    let quality = grasp.quality().unwrap();
    assert_eq!(quality.epsilon, -1.0);
    assert!(!quality.force_closure);
    assert!((quality.volume - 0.00392128283545).abs() < 0.01 * 0.00392128283545);
    let contacts = grasp.contacts().unwrap();
    assert_eq!(contacts.len(), 6);
    for c in &contacts {
        assert_eq!(c.body, BodyRef::Body(mug));
        assert!(matches!(c.link, BodyRef::Link { robot: 0, .. }));
        let n = (c.normal[0].powi(2) + c.normal[1].powi(2) + c.normal[2].powi(2)).sqrt();
        assert!((n - 1.0).abs() < 1e-9);
        assert!(world.name_of(c.link).unwrap().starts_with("Barrett_chain"));
    }
    assert_eq!(grasp.failure().unwrap(), "");
}

#[test]
fn errors_carry_status_and_place() {
    let missing = World::load("/no/such/world.xml", &LoadOptions::default())
        .err()
        .unwrap();
    assert_eq!(missing.status, Status::Input);
    assert!(
        missing.message.contains("/no/such/world.xml"),
        "{}",
        missing
    );

    let mut world = box_world();
    assert_eq!(
        world.body_name(99).err().unwrap().status,
        Status::OutOfRange
    );
    assert_eq!(
        world.find_body("nothing").err().unwrap().status,
        Status::NotFound
    );
    assert_eq!(world.dofs(0).err().unwrap().status, Status::OutOfRange);
    let nan = Pose {
        translation: [f64::NAN, 0.0, 0.0],
        rotation: [1.0, 0.0, 0.0, 0.0],
    };
    assert_eq!(
        world.set_body_pose(0, &nan).err().unwrap().status,
        Status::Input
    );
    assert_eq!(
        world.find_body("a\0b").err().unwrap().status,
        Status::InvalidArgument
    );
}

#[test]
fn dofs_and_their_errors() {
    let (mut world, _) = match planner_mug() {
        Some(w) => w,
        None => return,
    };
    let (min, max) = world.dof_limits(0).unwrap();
    assert_eq!(min.len(), 4);
    assert!((max[1] - 2.51327412287).abs() < 1e-9);
    world.set_dofs(0, &[0.1, 0.2, 0.3, 99.0]).unwrap();
    let dofs = world.dofs(0).unwrap();
    assert_eq!(dofs[2], 0.3);
    assert_eq!(dofs[3], max[3], "clamped");
    let wrong = world.set_dofs(0, &[0.1, 0.2]).err().unwrap();
    assert_eq!(wrong.status, Status::InvalidArgument);
    assert!(
        wrong.message.contains("2 values given, 4 expected"),
        "{}",
        wrong
    );
    assert_eq!(
        world.set_dofs(99, &[0.0; 4]).err().unwrap().status,
        Status::OutOfRange
    );
}

#[test]
fn clones_are_independent_and_saves_load_back() {
    let (world, data) = match planner_mug() {
        Some(w) => w,
        None => return,
    };
    let mut clone = world.try_clone().unwrap();
    clone.autograsp(0).unwrap();
    assert_eq!(world.dofs(0).unwrap(), vec![0.0; 4]);
    let closed = clone.dofs(0).unwrap();
    let file = scratch("save").join("closed.xml");
    clone.save(&file).unwrap();
    let back = World::load(&file, &LoadOptions::with_root(&data)).unwrap();
    for (a, b) in back.dofs(0).unwrap().iter().zip(&closed) {
        assert!((a - b).abs() < 1e-6);
    }
}

#[test]
fn rays_and_nearest_points_on_the_box() {
    let mut world = box_world();
    let mut scene = RayScene::new(&world, true).unwrap();
    let rays = [
        graspkit::ray([0.0, 0.0, 1000.0], [0.0, 0.0, -1.0]),
        graspkit::ray([0.0, 0.0, 1000.0], [0.0, 0.0, 1.0]),
    ];
    let hits = scene.intersect(&rays).unwrap();
    let hit = hits[0].unwrap();
    assert!((hit.distance - 940.0).abs() < 1e-3);
    assert!((hit.distance - (1000.0 - hit.point[2])).abs() < 1e-6);
    assert_eq!(hit.body, BodyRef::Body(0));
    assert!(hits[1].is_none());

    let nearest = scene.nearest(&[[100.0, 0.0, 0.0]], f64::INFINITY).unwrap();
    assert!((nearest[0].unwrap().distance - 70.0).abs() < 1e-9);

    world
        .set_body_pose(
            0,
            &Pose {
                translation: [0.0, 0.0, 10.0],
                ..Pose::IDENTITY
            },
        )
        .unwrap();
    scene.update(&world).unwrap();
    let mut raw = vec![graspkit::RawHit::default(); 1];
    scene.intersect_into(&rays[..1], &mut raw).unwrap();
    assert!((raw[0].distance - 930.0).abs() < 1e-3);

    let zero = graspkit::ray([0.0; 3], [0.0; 3]);
    let bad = scene.intersect(&[rays[0], zero]).err().unwrap();
    assert_eq!(bad.status, Status::Input);
    assert!(bad.message.contains("ray 1"), "{}", bad);
    assert_eq!(
        scene.intersect_into(&rays, &mut raw).err().unwrap().status,
        Status::InvalidArgument
    );
}

#[test]
fn planned_grasps_rank_and_reproduce() {
    let (world, _) = match planner_mug() {
        Some(w) => w,
        None => return,
    };
    let options = PlanOptions {
        steps: 3000,
        threads: 1,
        top: 5,
        ..PlanOptions::default()
    };
    let plan = Plan::run(&world, 0, 0, &options).unwrap();
    let grasps = plan.grasps();
    assert!(!grasps.is_empty() && grasps.len() <= 5);
    for pair in grasps.windows(2) {
        let (a, b) = (&pair[0], &pair[1]);
        assert!(a.force_closure >= b.force_closure);
        if a.force_closure == b.force_closure {
            assert!(a.epsilon >= b.epsilon);
        }
    }
    let closed = plan.grasp_world(0).unwrap();
    let again = closed.analyze_grasp(0, 0, WrenchSpace::L1).unwrap();
    let q = again.quality().unwrap();
    assert!((q.epsilon - grasps[0].epsilon).abs() < 1e-9);
    assert!((q.volume - grasps[0].volume).abs() < 1e-9);
    assert_eq!(again.contacts().unwrap().len() as i32, grasps[0].contacts);
    assert_eq!(plan.grasp_dofs(0, 4).unwrap(), closed.dofs(0).unwrap());
    assert_eq!(
        plan.grasp_world(99).err().unwrap().status,
        Status::OutOfRange
    );

    let unknown = PlanOptions {
        energy: "no-such-energy".to_string(),
        ..options
    };
    assert_eq!(
        Plan::run(&world, 0, 0, &unknown).err().unwrap().status,
        Status::Input
    );
}

#[test]
fn a_world_moves_to_another_thread() {
    fn assert_send<T: Send>() {}
    assert_send::<World>();
    assert_send::<graspkit::Grasp>();
    assert_send::<RayScene>();
    assert_send::<Plan>();
    let (world, _) = match planner_mug() {
        Some(w) => w,
        None => return,
    };
    let a = world.try_clone().unwrap();
    let b = world.try_clone().unwrap();
    let close = |mut w: World| {
        std::thread::spawn(move || {
            w.autograsp(0).unwrap();
            w.analyze_grasp(0, 0, WrenchSpace::L1)
                .unwrap()
                .contacts()
                .unwrap()
                .len()
        })
    };
    let (ta, tb) = (close(a), close(b));
    assert_eq!(ta.join().unwrap(), 6);
    assert_eq!(tb.join().unwrap(), 6);
}

#[test]
fn lua_scenarios() {
    let dir = scratch("lua");
    let exits = dir.join("exits.lua");
    std::fs::write(&exits, "os.exit(tonumber(arg[1]))\n").unwrap();
    let options = graspkit::ScriptOptions {
        args: vec!["3".to_string()],
        ..Default::default()
    };
    assert_eq!(graspkit::run_script(&exits, &options).unwrap(), 3);
    let fails = dir.join("fails.lua");
    std::fs::write(&fails, "error('boom')\n").unwrap();
    let e = graspkit::run_script(&fails, &Default::default())
        .err()
        .unwrap();
    assert_eq!(e.status, Status::Script);
    assert!(e.message.contains("boom"), "{}", e);
}

#[test]
fn plugins_and_warnings() {
    let plugins = graspkit::plugins_scan().unwrap();
    assert!(
        plugins.iter().any(|p| p.name == "barrett" && p.loaded),
        "{:?}",
        plugins
    );
    assert!(graspkit::plugin_search_path()
        .unwrap()
        .contains("graspkit/plugins"));
    let fake = scratch("plugin").join("fake.so");
    std::fs::write(&fake, "not an ELF file").unwrap();
    assert_eq!(
        graspkit::plugin_load(&fake).err().unwrap().status,
        Status::Input
    );

    // A body file with an unknown tag on line 4 warns, naming it.
    let dir = scratch("log");
    std::fs::copy(project().join("models/objects/box.iv"), dir.join("box.iv")).unwrap();
    let file = dir.join("odd.xml");
    std::fs::write(
        &file,
        "<?xml version=\"1.0\" ?>\n<root>\n  <material>wood</material>\n  <colour>red</colour>\n  <geometryFile type=\"Inventor\">box.iv</geometryFile>\n</root>\n",
    )
    .unwrap();
    let seen = Arc::new(AtomicUsize::new(0));
    let counter = seen.clone();
    graspkit::set_log_callback(Some(Box::new(move |r: &graspkit::LogRecord| {
        if r.kind == "unknown-element"
            && r.element == "colour"
            && r.line == 4
            && r.file.ends_with("odd.xml")
        {
            counter.fetch_add(1, Ordering::SeqCst);
        }
    })))
    .unwrap();
    World::load(&file, &LoadOptions::default()).unwrap();
    graspkit::set_log_callback(None).unwrap();
    assert_eq!(seen.load(Ordering::SeqCst), 1);
}

#[test]
fn views_of_bodies_and_robots() {
    let (world, _) = match planner_mug() {
        Some(w) => w,
        None => return,
    };
    let bodies = world.bodies().unwrap();
    assert_eq!(bodies.len(), 1);
    assert_eq!(bodies[0].name().unwrap(), "mug");
    assert_eq!(bodies[0].mass().unwrap().0, 200.0); // GraspIt!'s mug.xml: 200 g
    let robot = world.robot(0).unwrap();
    assert_eq!(robot.name().unwrap(), "Barrett");
    let poses = robot.link_poses().unwrap();
    // Barrett.xml: two fingers of three links, the thumb of two.
    let links: Vec<usize> = poses.iter().map(|c| c.len()).collect();
    assert_eq!(links, vec![3, 3, 2]);
    // The palm is the robot's base.
    assert_eq!(robot.link_pose(-1, -1).unwrap(), robot.pose().unwrap());
    assert_eq!(poses[1][2], robot.link_pose(1, 2).unwrap());
    assert_eq!(world.robot(1).err().unwrap().status, Status::OutOfRange);
    assert_eq!(world.body(-1).err().unwrap().status, Status::OutOfRange);
}
