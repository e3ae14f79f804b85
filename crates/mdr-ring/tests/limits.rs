//! Populations a user can type are bounded before anything is allocated: a particle count or a
//! surface density beyond `MAX_PARTICLES` is refused with an error that names the parameter and
//! the limit, instead of exhausting memory.

use mdr_ring::particles::MAX_PARTICLES;
use mdr_ring::prelude::*;

fn refused(config: RingConfig) -> String {
    let law = ConstantRestitution::new(0.5).unwrap();
    match RingSimulation::new(config, law) {
        Ok(_) => panic!("the population was accepted"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn particle_counts_beyond_the_limit_are_refused_by_name() {
    for count in [0, MAX_PARTICLES + 1, usize::MAX] {
        let message = refused(RingConfig::default().particles(count));
        assert!(message.contains("`particles`"), "{count}: {message}");
        assert!(message.contains("10000000"), "{count}: {message}");
    }
}

#[test]
fn surface_densities_that_ask_for_too_many_particles_are_refused_by_name() {
    // REBOUND's Σ = 400 kg/m² on a 200 m box draws ≈ 1,300 particles; 10⁷ times as dense asks
    // for ≈ 1.3·10¹⁰.
    let message = refused(RingConfig::default().surface_density(4.0e9));
    assert!(message.contains("`surface_density`"), "{message}");
    assert!(message.contains("MAX_PARTICLES"), "{message}");
}
