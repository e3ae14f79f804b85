//! The smallest program that adds the MDR law to a rapier world (force mode): the paper's steel
//! ball hits a steel floor at 1 m/s under gravity and bounces.
//! Run: `cargo run --release --example drop`.
use mdr_rapier::prelude::*;
use mdr_rapier::rapier::prelude::*;
use mdr_rapier::LawPair;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (radius, v0) = (0.635e-2, 1.0);
    let steel = Material::paper_steel();
    let mut world = PhysicsWorld::default();
    world.integration_parameters.length_unit = 2.0 * radius;

    // The law: MDR normal (paper's q_c and Θ/E*) with Mindlin friction.
    let model = ContactModel::new(MdrElastoPlastic::paper()).with_tangential(Mindlin::new(0.3)?);
    let mut stepper = ForceModeStepper::new(model);
    let m = stepper.particles_mut().insert_material(steel);
    let floor = ColliderBuilder::new(SharedShape::halfspace(Vector::Y));
    stepper.insert_surface(&mut world, floor, None, m)?;
    let ball = SphereBuilder::new(radius, m)
        .translation(Vector::new(0.0, radius + 1e-5, 0.0))
        .linvel(Vector::new(0.0, -v0, 0.0));
    let (ball, _) = stepper.insert_sphere(&mut world, ball)?;

    // 100 steps per Hertz contact at the impact speed; rapier then integrates exactly.
    let pair = LawPair::sphere_on_half_space(radius, &steel, &steel)?;
    let dt = stable_time_step(&pair, v0, 100.0)?.time_step;
    stepper.configure(&mut world.integration_parameters, dt, 0.1 * radius)?;

    let (mut touched, mut steps) = (false, 0);
    loop {
        let report = stepper.step(&mut world)?;
        if report.contacts > 0 {
            touched = true;
            steps += 1;
        } else if touched {
            break;
        }
    }
    let e = world.bodies[ball].linvel().y / v0;
    let law = MdrElastoPlastic::paper().bind(&pair)?;
    let reference = law.impact(&MdrState::default(), pair.reduced_mass(), v0)?;
    println!("contact resolved in {steps} steps of {dt:.3e} s");
    println!("e_n in rapier     = {e:.5}");
    println!("e_n energy route  = {:.5}", reference.restitution);
    Ok(())
}
