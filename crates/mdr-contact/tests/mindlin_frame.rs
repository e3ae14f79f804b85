//! The Mindlin frame update: when the contact plane turns, the stored displacement is projected
//! into the new plane and keeps its length. Small tilts take a series for the length factor,
//! large ones the exact square root; both must agree with the textbook sequence (project, then
//! rescale by |ξ|/|ξ_⊥|) to round-off, on either side of the switch.

use mdr_contact::nalgebra::Vector3;
use mdr_contact::prelude::*;

#[test]
fn a_turning_contact_plane_keeps_the_displacement_length_for_small_and_large_tilts() {
    let pair = ContactPair::new(1.5e5, 28_571.0, 0.25, 1.0).unwrap();
    // μ large: no slip, so the update is the frame update plus a zero increment.
    let law = Mindlin::new(1e6).unwrap().bind(&pair).unwrap();
    let response = NormalResponse {
        force: 1.0,
        contact_radius: 1e-2,
        stiffness: 1e3,
    };
    let xi = Vector3::new(3e-4, -1e-4, 0.0);
    // Tilts of the normal about the x axis: t = (n·ξ)²/|ξ|² from 1e-16 to 0.5, across the
    // switch at t = 1e-6.
    for tilt in [1e-8_f64, 1e-5, 3e-4, 9.9e-4, 1.01e-3, 3e-3, 0.1, 0.7] {
        let n = Vector3::new(0.0, tilt.sin(), tilt.cos());
        let mut state = MindlinState {
            displacement: xi,
            contact_radius: response.contact_radius,
        };
        let out = law.update(
            &mut state,
            &TangentialInput {
                normal: n,
                displacement_increment: Vector3::zeros(),
                normal_response: response,
            },
        );
        assert!(!out.sliding);
        let projected = xi - n * n.dot(&xi);
        let textbook = projected * (xi.norm() / projected.norm());
        let got = state.displacement;
        assert!(
            (got - textbook).norm() <= 4.0 * f64::EPSILON * xi.norm(),
            "tilt {tilt}: {got:?} vs {textbook:?}"
        );
        assert!(
            got.dot(&n).abs() <= 4.0 * f64::EPSILON * xi.norm(),
            "tilt {tilt}: in plane"
        );
        let t = (n.dot(&xi) / xi.norm()).powi(2);
        assert!(t > 0.0, "tilt {tilt}: the plane turned under ξ");
    }
}
