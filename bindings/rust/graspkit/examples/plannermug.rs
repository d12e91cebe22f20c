//! A Rust host: load a world, close its first hand on its first graspable body, print the grasp
//! as `graspkit grasp WORLD --autograsp` prints it (the same lines, so the two can be compared).
//!   cargo run --example plannermug -- WORLD [ROOT]

use std::process::exit;

/// C's `%.7g`, which the command-line program prints with.
fn g7(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{}", x);
    }
    let scientific = format!("{:.6e}", x);
    let (mantissa, exponent) = scientific.split_at(scientific.find('e').unwrap());
    let exponent: i32 = exponent[1..].parse().unwrap();
    let trim = |s: &str| -> String {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s.to_string()
        }
    };
    if !(-4..7).contains(&exponent) {
        let sign = if exponent < 0 { '-' } else { '+' };
        format!("{}e{}{:02}", trim(mantissa), sign, exponent.abs())
    } else {
        trim(&format!("{:.*}", (6 - exponent) as usize, x))
    }
}

fn run(args: &[String]) -> graspkit::Result<()> {
    let options = match args.get(2) {
        Some(root) => graspkit::LoadOptions::with_root(root),
        None => graspkit::LoadOptions::default(),
    };
    let mut world = graspkit::World::load(&args[1], &options)?;
    let hand = world.first_hand()?;
    let mut object = None;
    for body in 0..world.body_count()? {
        if world.is_graspable(body)? {
            object = Some(body);
            break;
        }
    }
    let object = match object {
        Some(body) => body,
        None => {
            eprintln!("plannermug: the world has no graspable body");
            exit(1);
        }
    };
    world.autograsp(hand)?;
    let grasp = world.analyze_grasp(hand, object, graspkit::WrenchSpace::L1)?;
    let quality = grasp.quality()?;
    println!("{} contacts with the object", grasp.contacts()?.len());
    println!("epsilon {}", g7(quality.epsilon));
    println!("volume {}", g7(quality.volume));
    println!(
        "force closure {}",
        if quality.force_closure { "yes" } else { "no" }
    );
    Ok(())
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 2 {
        eprintln!("usage: plannermug WORLD [ROOT]");
        exit(2);
    }
    if let Err(e) = run(&args) {
        eprintln!("plannermug: {}", e);
        exit(1);
    }
}
