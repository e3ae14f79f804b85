//! The work books of a contact state are diagnostics: a state without them ([`NoBooks`]) gives
//! the same forces and the same normal and tangential histories bit for bit, takes 32 bytes
//! less, and reports NaN for the friction and damping work and the springs' stiffness energy.

use mdr_contact::nalgebra::Vector3;
use mdr_contact::prelude::*;

#[test]
fn states_without_books_follow_the_booked_ones_bit_for_bit() {
    // The settled-bed pair of `benches/lammps` with the MDR law, Mindlin friction and both
    // dashpots: an impact that yields, shears, slides and unloads.
    let pair = ContactPair::new(1.5e5, 28_571.0, 0.25, std::f64::consts::PI / 12.0).unwrap();
    let law = ContactModel::new(MdrElastoPlastic::new(10.0, 0.37).unwrap())
        .with_tangential(Mindlin::new(0.5).unwrap())
        .with_damping(
            HertzianViscous::new(50.0)
                .unwrap()
                .with_tangential_ratio(0.5)
                .unwrap(),
        )
        .bind(&pair)
        .unwrap();
    let mut booked = law.new_state();
    let mut unbooked: ContactState<_, _, NoBooks> = ContactState::default();
    let (mut slid, mut stuck) = (0, 0);
    for step in 0..400 {
        let t = step as f64 / 400.0;
        let input = ContactInput {
            overlap: 2e-3 * (std::f64::consts::PI * t).sin(),
            // The contact plane tilts as it goes, and the tangential motion reverses.
            normal: Vector3::new(0.05 * t, 0.0, 1.0).normalize(),
            relative_velocity: Vector3::new(0.4 * (9.0 * t).cos(), 0.1, -0.02),
            dt: 1e-4,
        };
        let a = law.update(&mut booked, &input);
        let b = law.update(&mut unbooked, &input);
        assert_eq!(a, b, "step {step}");
        assert_eq!(booked.normal, unbooked.normal);
        assert_eq!(booked.tangential, unbooked.tangential);
        if a.tangential.sliding {
            slid += 1;
        } else if a.normal_force > 0.0 {
            stuck += 1;
        }
    }
    assert!(
        slid > 10 && stuck > 10,
        "{slid} sliding and {stuck} sticking steps"
    );
    assert!(booked.books.friction_work > 0.0 && booked.books.damping_work > 0.0);
    // The contact opened at the end: its spring released what it held, after gaining and
    // losing energy with the stiffness along the way.
    assert!(booked.books.tangential_stiffness_energy != 0.0);
    assert!(unbooked.books.tangential_stiffness_energy().is_nan());
    let report = law.report(&unbooked, 1e-3);
    assert!(report.friction_work.is_nan() && report.damping_work.is_nan());
    assert_eq!(report.max_overlap, law.report(&booked, 1e-3).max_overlap);
    assert_eq!(
        std::mem::size_of_val(&booked),
        std::mem::size_of_val(&unbooked) + 32
    );
}
