//! The table of `docs/verification.md` §3: test 4 (aluminium oxide sphere, R = 2.5 mm, 3.9 m/s,
//! μ = 0.092, rigid plane, elastic) against the Kharaz, Gorham & Salman (2001) points at every
//! experimental angle, for the validator with the Mindlin law and with the MDR spring bed.
//! `cargo run --release -p mdr-verify --example kharaz_table [STEPS_PER_CONTACT] [SPRINGS]`.

use mdr_verify::{kharaz, materials, Backend, Collision, CollisionOutcome, Target};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let steps: usize = args.next().map(|a| a.parse()).transpose()?.unwrap_or(4000);
    let springs: usize = args.next().map(|a| a.parse()).transpose()?.unwrap_or(2000);
    let m = materials::aluminium_oxide();
    let run = |angle: f64, backend: Backend| -> Result<(Collision, CollisionOutcome), _> {
        let r = angle.to_radians();
        let c = Collision {
            tangential_speed: 3.9 * r.sin(),
            friction: mdr_verify::chung_ooi::MU_4,
            steps_per_contact: steps,
            ..Collision::head_on(
                0.0025,
                m,
                Target::Plane {
                    material: materials::rigid_for(&m),
                },
                3.9 * r.cos(),
            )
        };
        c.run(backend).map(|o| (c, o))
    };
    type Quantity = fn(&Collision, &CollisionOutcome) -> f64;
    type Row = (&'static str, &'static [(f64, f64)], Quantity);
    let quantities: [Row; 4] = [
        ("e_t", &kharaz::TANGENTIAL_RESTITUTION, |c, o| {
            o.tangential_velocity / c.tangential_speed
        }),
        ("ω' (rad/s)", &kharaz::SPIN, |_, o| o.spin),
        (
            "rebound angle, centre (°)",
            &kharaz::REBOUND_ANGLE_CENTRE,
            |c, o| {
                o.tangential_velocity
                    .atan2(o.normal_restitution * c.normal_speed)
                    .to_degrees()
            },
        ),
        (
            "rebound angle, contact point (°)",
            &kharaz::REBOUND_ANGLE_CONTACT,
            |c, o| {
                (o.tangential_velocity - c.radius * o.spin)
                    .atan2(o.normal_restitution * c.normal_speed)
                    .to_degrees()
            },
        ),
    ];
    println!("{steps} steps per contact, {springs} springs\n");
    println!("| quantity | θ (°) | experiment | validator, Mindlin | validator, MDR spring bed |");
    println!("|---|---|---|---|---|");
    for (name, data, quantity) in quantities {
        for &(angle, experiment) in data {
            let (c, mindlin) = run(angle, Backend::ValidatorMindlin)?;
            let (_, bed) = run(angle, Backend::ValidatorSpringBed { springs })?;
            println!(
                "| {name} | {angle:.1} | {experiment:.4} | {:.4} | {:.4} |",
                quantity(&c, &mindlin),
                quantity(&c, &bed)
            );
        }
    }
    Ok(())
}
