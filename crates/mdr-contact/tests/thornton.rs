//! Thornton (1997): the restitution coefficient obtained by integrating `ThorntonLaw` in time
//! matches the published closed form `e(v/v_y)` (his eq. 31, `thornton_restitution`) within 1 %.

mod common;

use mdr_contact::normal::thornton_restitution;
use mdr_contact::prelude::*;

#[test]
fn time_stepped_restitution_matches_thorntons_closed_form() {
    let pair = ContactPair::paper_fig2();
    let law = Thornton::new(1.0e9).unwrap().bind(&pair).unwrap();
    let mass = pair.reduced_mass();
    let v_y = law.yield_speed(mass);
    for ratio in [2.0, 5.0, 10.0, 50.0] {
        let speed = ratio * v_y;
        let mut state = ThorntonState::default();
        let t_c = pair.hertz_contact_time(speed);
        let run = common::impact(&law, &mut state, mass, speed, t_c, 20_000);
        assert!(run.steps >= 5_000, "only {} steps in contact", run.steps);
        let published = thornton_restitution(ratio);
        assert!(
            (run.restitution / published - 1.0).abs() < 0.01,
            "v/v_y = {ratio}: integrated e = {}, Thornton e = {published}",
            run.restitution
        );
    }
}

#[test]
fn below_the_yield_speed_the_impact_is_elastic() {
    let pair = ContactPair::paper_fig2();
    let law = Thornton::new(1.0e9).unwrap().bind(&pair).unwrap();
    let mass = pair.reduced_mass();
    let speed = 0.9 * law.yield_speed(mass);
    let mut state = ThorntonState::default();
    let run = common::impact(
        &law,
        &mut state,
        mass,
        speed,
        pair.hertz_contact_time(speed),
        20_000,
    );
    assert!(
        (run.restitution - 1.0).abs() < 1e-4,
        "e = {}",
        run.restitution
    );
    assert_eq!(thornton_restitution(0.9), 1.0);
    assert_eq!(law.residual_overlap(&state), 0.0);
}
