//! The Hertz law's history is the largest overlap so far (what the scenes report as `d_max`
//! for a Hertz contact): it grows with the overlap and never shrinks on unloading. Written for
//! the mutants of `HertzLaw::update` that a restitution or force check cannot see (Hertz is
//! elastic, so its force does not depend on the history).

use mdr_contact::prelude::*;

#[test]
fn hertz_state_is_the_largest_overlap_so_far() {
    let pair = ContactPair::paper_fig2();
    let law = Hertz.bind(&pair).unwrap();
    let mut state = 0.0;
    for (overlap, largest) in [
        (1.0e-6, 1.0e-6),
        (3.0e-6, 3.0e-6),
        (2.0e-6, 3.0e-6),
        (3.0e-6, 3.0e-6),
        (4.0e-6, 4.0e-6),
        (-1.0e-6, 4.0e-6),
    ] {
        let response = law.update(&mut state, overlap);
        assert_eq!(state, largest, "after overlap {overlap}");
        // The force is Hertz's at the current overlap whatever the history.
        let hertz = law.force(overlap);
        assert!(
            (response.force - hertz).abs() <= 1e-14 * hertz,
            "{} vs {hertz}",
            response.force
        );
    }
}
