//! The parity request through the Rust crate (tests/parity/parity_test.py runs it).
//! Usage: parity PLANNER_WORLD ROOT GRASP_WORLD STEPS SEED TOP SECONDS HAND OUT
//! Prints one JSON object: plan, grasp, validation, simulation, dataset (parity_test.py's
//! schema).

use graspkit::{
    generate_object, Dataset, DatasetOptions, LoadOptions, Plan, PlanOptions, Pose,
    SimulationOptions, World, WrenchSpace,
};

fn pose7(p: &Pose) -> String {
    let v: Vec<String> = p
        .translation
        .iter()
        .chain(p.rotation.iter())
        .map(|x| format!("{:e}", x))
        .collect();
    format!("[{}]", v.join(", "))
}

fn first_graspable(world: &World) -> graspkit::Result<i32> {
    for b in 0..world.body_count()? {
        if world.is_graspable(b)? {
            return Ok(b);
        }
    }
    panic!("no graspable body");
}

fn main() -> graspkit::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    assert_eq!(args.len(), 10, "usage: parity PLANNER_WORLD ROOT GRASP_WORLD STEPS SEED TOP SECONDS HAND OUT");
    let (planner_world, root, grasp_world) = (&args[1], &args[2], &args[3]);
    let seconds: f64 = args[7].parse().unwrap();
    let load = LoadOptions::with_root(root);

    let mut world = World::load(planner_world, &load)?;
    let hand = world.first_hand()?;
    let options = PlanOptions {
        steps: args[4].parse().unwrap(),
        seed: args[5].parse().unwrap(),
        top: args[6].parse().unwrap(),
        ..PlanOptions::default()
    };
    let plan = Plan::run(&world, hand, first_graspable(&world)?, &options)?;
    let grasps: Vec<String> = plan
        .grasps()
        .iter()
        .map(|g| {
            format!(
                "{{\"epsilon\": {:e}, \"volume\": {:e}, \"contacts\": {}, \"force_closure\": {}, \"pose\": {}}}",
                g.epsilon, g.volume, g.contacts, g.force_closure, pose7(&g.closed)
            )
        })
        .collect();

    world.autograsp(hand)?;
    let grasp = world.analyze_grasp(hand, first_graspable(&world)?, WrenchSpace::L1)?;
    let quality = grasp.quality()?;
    let contacts = grasp.contacts()?.len();

    let held = World::load(grasp_world, &load)?.validate(seconds)?;
    let slips: Vec<String> = held.directions.iter().map(|d| format!("{:e}", d.slip)).collect();

    let mut moving = World::load(grasp_world, &load)?;
    let run = moving.simulate(&SimulationOptions {
        seconds,
        autograsp: true,
        ..SimulationOptions::default()
    })?;
    let mut bodies = Vec::new();
    for b in 0..moving.body_count()? {
        bodies.push(pose7(&moving.body_pose(b)?));
    }
    let mut dofs = Vec::new();
    for r in 0..moving.robot_count()? {
        dofs.extend(moving.dofs(r)?.iter().map(|v| format!("{:e}", v)));
    }
    // One generated object's dataset: planned, saved, read back.
    let object = generate_object(&args[9], 2, 0)?;
    let options = DatasetOptions {
        grasps: 3,
        steps: 1500,
        seed: 5,
        ..DatasetOptions::default()
    };
    let file = format!("{}/dataset.h5", args[9]);
    Dataset::plan(&args[8], &object, &LoadOptions::default(), &options)?.save(&file)?;
    let dataset: Vec<String> = Dataset::load(&file)?
        .grasps()
        .iter()
        .map(|g| {
            format!(
                "{{\"epsilon\": {:e}, \"volume\": {:e}, \"force_closure\": {}, \"pose\": {}}}",
                g.epsilon, g.volume, g.force_closure, pose7(&g.grasp)
            )
        })
        .collect();
    println!(
        "{{\"plan\": [{}], \"grasp\": {{\"epsilon\": {:e}, \"volume\": {:e}, \"contacts\": {}, \"force_closure\": {}}}, \
         \"validation\": {{\"held\": {}, \"directions_held\": {}, \"settle_seconds\": {:e}, \"slip\": [{}]}}, \
         \"simulation\": {{\"completed\": {}, \"steps\": {}, \"time\": {:e}, \"bodies\": [{}], \"dofs\": [{}]}}, \"dataset\": [{}]}}",
        grasps.join(", "),
        quality.epsilon,
        quality.volume,
        contacts,
        quality.force_closure,
        held.held,
        held.directions_held,
        held.settle_seconds,
        slips.join(", "),
        run.completed,
        run.steps,
        run.time,
        bodies.join(", "),
        dofs.join(", "),
        dataset.join(", ")
    );
    Ok(())
}
