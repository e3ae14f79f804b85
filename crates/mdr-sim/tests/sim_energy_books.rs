//! Energy books of a small column collapse with no external work and no damping: the sum of
//! kinetic, gravitational and elastic energy and of the plastic work stays within 0.03 % of its
//! start value (measured 0.0092 %; 0.018 % and 0.010 % with friction and rolling resistance,
//! held to 0.05 %), while plasticity dissipates a sizeable part of the released energy (so the test
//! fails if the plastic work were not booked, or booked twice).

mod common;

use mdr_sim::output::energy::EnergyRow;
use mdr_sim::{run_scene, scene::validate::parse_scene, RunOptions};

/// Largest `|balance − start|` of the rows if the book `left_out` were not part of the balance.
fn worst_drift_without(rows: &[EnergyRow], left_out: impl Fn(&EnergyRow) -> f64) -> f64 {
    let start = rows[0].balance_j - left_out(&rows[0]);
    rows.iter()
        .map(|r| (r.balance_j - left_out(r) - start).abs())
        .fold(0.0, f64::max)
}

#[test]
fn frictionless_column_collapse_keeps_the_energy_sum() {
    let dir = common::temp_dir("energy");
    let text = common::column(4, 4, 0.06, 0.0, "");
    let path = common::write(&dir, "column.toml", &text);
    let scene = parse_scene(&path, &text).expect("valid scene");
    let summary = run_scene(
        &scene,
        &RunOptions::new(dir.join("out")).quiet(true).no_frames(true),
    )
    .expect("run");
    let rows = &summary.energy;
    let start = rows[0].balance_j;
    let released = rows[0].gravitational_j
        - rows
            .iter()
            .map(|r| r.gravitational_j)
            .fold(f64::INFINITY, f64::min);
    let worst = rows
        .iter()
        .map(|r| (r.balance_j - start).abs())
        .fold(0.0, f64::max);
    let last = rows.last().unwrap();
    eprintln!(
        "start {start:.6e} J, released {released:.3e} J, plastic {:.3e} J, worst drift {worst:.3e} J ({:.4} %)",
        last.plastic_j,
        100.0 * worst / start
    );
    assert!(
        worst <= 3e-4 * start,
        "energy sum drifted by {worst:.3e} J of {start:.3e} J"
    );
    // The books are not trivially conserved: the collapse releases energy and plasticity takes a
    // visible part of it; the drift is also small against the released energy alone.
    assert!(
        released > 0.05 * start,
        "the column barely moved: {released:.3e} J"
    );
    assert!(
        last.plastic_j > 0.05 * released,
        "plastic work {:.3e} J",
        last.plastic_j
    );
    assert!(
        worst < 0.1 * last.plastic_j,
        "drift {worst:.3e} J vs plastic {:.3e} J",
        last.plastic_j
    );
}

/// With Mindlin friction the books hold too: slip work is booked as friction, the stored
/// tangential energy as elastic, and the energy the spring gains or loses without work because
/// its stiffness follows the contact radius (and a shrinking contact rescales its displacement)
/// as `stiffness_tangential_j`. Bound: 0.05 % of the start value (measured 0.018 %; 0.14 % without
/// the stiffness book, which the last assertion checks is needed).
#[test]
fn frictional_column_collapse_books_friction() {
    let dir = common::temp_dir("energy-friction");
    let text = common::column(4, 4, 0.06, 0.5, "");
    let path = common::write(&dir, "column.toml", &text);
    let scene = parse_scene(&path, &text).expect("valid scene");
    let summary = run_scene(
        &scene,
        &RunOptions::new(dir.join("out")).quiet(true).no_frames(true),
    )
    .expect("run");
    let rows = &summary.energy;
    let start = rows[0].balance_j;
    let worst = rows
        .iter()
        .map(|r| (r.balance_j - start).abs())
        .fold(0.0, f64::max);
    let last = rows.last().unwrap();
    eprintln!(
        "friction: start {start:.6e} J, plastic {:.3e} J, friction {:.3e} J, worst drift {worst:.3e} J ({:.4} %)",
        last.plastic_j,
        last.friction_j,
        100.0 * worst / start
    );
    assert!(
        worst <= 0.0005 * start,
        "energy sum drifted by {worst:.3e} J of {start:.3e} J (more than 0.05 %)"
    );
    assert!(last.friction_j > 0.0, "no friction work booked");
    // The tangential springs' stiffness book is needed: without it the drift is several times
    // larger (measured: 0.018 % with it, see the eprintln for without).
    let without = worst_drift_without(rows, |r| r.stiffness_tangential_j);
    eprintln!(
        "friction: stiffness_tangential {:.3e} J; worst drift without it {without:.3e} J ({:.4} %)",
        last.stiffness_tangential_j,
        100.0 * without / start
    );
    assert!(
        without > 3.0 * worst,
        "drift {worst:.3e} J with the stiffness book, {without:.3e} J without"
    );
}

/// With rolling resistance (Ai et al.'s elastic–plastic spring, μ_r = 0.1) the books hold as
/// well: the rolling springs' energy `|M_r|²/(2 k_r)` is booked as `elastic_rolling_j` and the
/// plastic rolling rotation's work as `rolling_j`. Besides 0.05 % of the start value (which
/// includes the whole potential energy above the floor), the drift is held to 2 % of the
/// energy the collapse releases and to half the rolling work: leaving the rolling work out of
/// the sum would break both (it is ~7 % of the released energy). The energy the tangential and
/// rolling springs gain or lose without work through their stiffness changes is booked as
/// `stiffness_tangential_j` and `stiffness_rolling_j`: measured drift with every book 0.010 % of
/// the start value (0.14 % of the released energy); without the tangential stiffness book
/// 0.16 %, without the rolling one 0.09 %. The drift is held to 0.05 % of the start value and to
/// a third of what it would be without either stiffness book (so a missing, mis-signed or
/// wrongly evaluated stiffness book fails the test).
#[test]
fn rolling_resistance_column_collapse_books_rolling() {
    let dir = common::temp_dir("energy-rolling");
    let text = common::column(4, 4, 0.06, 0.5, "")
        .replace("friction = 0.5", "friction = 0.5\nrolling_friction = 0.1");
    let path = common::write(&dir, "column.toml", &text);
    let scene = parse_scene(&path, &text).expect("valid scene");
    let summary = run_scene(
        &scene,
        &RunOptions::new(dir.join("out")).quiet(true).no_frames(true),
    )
    .expect("run");
    let rows = &summary.energy;
    let start = rows[0].balance_j;
    let released = rows[0].gravitational_j
        - rows
            .iter()
            .map(|r| r.gravitational_j)
            .fold(f64::INFINITY, f64::min);
    let worst = rows
        .iter()
        .map(|r| (r.balance_j - start).abs())
        .fold(0.0, f64::max);
    let last = rows.last().unwrap();
    let peak_rolling_elastic = rows.iter().map(|r| r.elastic_rolling_j).fold(0.0, f64::max);
    eprintln!(
        "rolling: start {start:.6e} J, released {released:.3e} J, plastic {:.3e} J, friction {:.3e} J, rolling {:.3e} J, \
         peak rolling elastic {peak_rolling_elastic:.3e} J, worst drift {worst:.3e} J ({:.4} %)",
        last.plastic_j,
        last.friction_j,
        last.rolling_j,
        100.0 * worst / start
    );
    assert!(
        worst <= 0.0005 * start,
        "energy sum drifted by {worst:.3e} J of {start:.3e} J (more than 0.05 %)"
    );
    assert!(
        worst <= 0.02 * released,
        "energy sum drifted by {worst:.3e} J, released {released:.3e} J"
    );
    assert!(
        last.rolling_j > 0.04 * released,
        "rolling work {:.3e} J would not show against the released energy",
        last.rolling_j
    );
    assert!(
        worst < 0.5 * last.rolling_j,
        "drift {worst:.3e} J vs rolling work {:.3e} J",
        last.rolling_j
    );
    assert!(
        peak_rolling_elastic > 0.0,
        "no rolling spring energy booked"
    );
    let without_t = worst_drift_without(rows, |r| r.stiffness_tangential_j);
    let without_r = worst_drift_without(rows, |r| r.stiffness_rolling_j);
    eprintln!(
        "rolling: stiffness_tangential {:.3e} J, stiffness_rolling {:.3e} J; worst drift without \
         them {without_t:.3e} J ({:.4} %), {without_r:.3e} J ({:.4} %)",
        last.stiffness_tangential_j,
        last.stiffness_rolling_j,
        100.0 * without_t / start,
        100.0 * without_r / start
    );
    assert!(
        without_t > 3.0 * worst && without_r > 3.0 * worst,
        "drift {worst:.3e} J with the stiffness books, {without_t:.3e} J without the tangential \
         one, {without_r:.3e} J without the rolling one"
    );
}

/// The 640-sphere column collapse of docs/theory.md §5.1's energy-audit table (aspect ratio
/// 1.83, MDR + Mindlin, with and without rolling resistance, 0.4 s).
const AUDIT_COLUMN: &str = r#"
[run]
name = "column"
seed = 7
duration_s = 0.4
dt_s = "auto"
max_speed_m_per_s = 1.2
output_interval_s = 0.01
headline = "column"

[gravity]
acceleration_m_per_s2 = [0.0, 0.0, -9.81]

[[material]]
name = "grain"
youngs_pa = 5.0e7
poisson_ratio = 0.25
density_kg_per_m3 = 2500.0

[[material]]
name = "floor"
youngs_pa = 5.0e7
poisson_ratio = 0.25
density_kg_per_m3 = 2500.0

[contact]
normal = "mdr"
critical_line_load_n_per_m = 500.0
hardening_ratio = 0.37
tangential = "mindlin"
friction = 0.5
rolling_friction = 0.1

[[particles]]
material = "grain"
count = 640
radius_m = 0.002
placement = "lattice"
region_min_m = [-0.0172, -0.0172, 0.0]
region_max_m = [0.0172, 0.0172, 0.05]
gap_fraction = 0.05
jitter_fraction = 0.8

[[walls]]
kind = "plane"
material = "floor"
point_m = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
"#;

/// The books of docs/theory.md §5.1's audit table that the energy CSV carries, in % of the
/// start energy at the end of the run: `C_t` (`−stiffness_tangential_j`), `C_r`
/// (`−stiffness_rolling_j`) and the `balance_j` drift, at the automatic time step and at half of
/// it, with and without rolling resistance. Printed as the table's rows; held to what the table
/// says of them: the drift without rolling resistance is a first-order time-step error (it
/// halves with `dt`, ratio 2 ± 0.2), with rolling resistance the two gaps nearly cancel (drift
/// below 0.1 % at both steps), and the stiffness books are converged (`C_t` and `C_r` move by
/// less than 10 % from `dt` to `dt/2`). Long (four runs of 96 000 to 192 000 steps):
/// `cargo test -p mdr-sim --test sim_energy_books -- --ignored --nocapture column_640`.
#[test]
#[ignore]
fn column_640_stiffness_books_and_time_step_gap() {
    let dir = common::temp_dir("energy-audit");
    let auto_dt = {
        let path = common::write(&dir, "auto.toml", AUDIT_COLUMN);
        parse_scene(&path, AUDIT_COLUMN).expect("valid scene").dt
    };
    // (C_t, C_r, drift) in % of the start energy.
    let run = |name: &str, rolling: bool, dt: f64| -> [f64; 3] {
        let mut text = AUDIT_COLUMN.replace("dt_s = \"auto\"", &format!("dt_s = {dt:e}"));
        if !rolling {
            text = text.replace("rolling_friction = 0.1\n", "");
        }
        let path = common::write(&dir, &format!("{name}.toml"), &text);
        let scene = parse_scene(&path, &text).expect("valid scene");
        assert_eq!(scene.particles.len(), 640);
        let summary = run_scene(
            &scene,
            &RunOptions::new(dir.join(name)).quiet(true).no_frames(true),
        )
        .expect("run");
        let (first, last) = (&summary.energy[0], summary.energy.last().unwrap());
        let e0 = first.balance_j;
        let percent = |x: f64| 100.0 * x / e0;
        // The table's `C_t` and `C_r` are the energies the springs gained without work: the
        // columns book what they lost, `−Σ C`.
        let books = [
            -percent(last.stiffness_tangential_j),
            -percent(last.stiffness_rolling_j),
            percent(last.balance_j - e0),
        ];
        eprintln!(
            "{name}: dt = {dt:.4e} s, E0 = {e0:.6e} J, t = {:.4} s: C_t {:+.2} %, C_r {:+.2} %, \
             balance_j drift {:+.3} %",
            last.time_s, books[0], books[1], books[2]
        );
        books
    };
    let rolling = run("rolling_dt", true, auto_dt);
    let rolling_half = run("rolling_half_dt", true, 0.5 * auto_dt);
    let plain = run("mindlin_dt", false, auto_dt);
    let plain_half = run("mindlin_half_dt", false, 0.5 * auto_dt);
    let ratio = plain[2] / plain_half[2];
    assert!(
        (1.8..2.2).contains(&ratio),
        "drift {plain:?} vs {plain_half:?}"
    );
    assert!(rolling[2].abs() < 0.1 && rolling_half[2].abs() < 0.1);
    for (a, b) in [
        (rolling[0], rolling_half[0]),
        (rolling[1], rolling_half[1]),
        (plain[0], plain_half[0]),
    ] {
        assert!((a - b).abs() < 0.1 * a.abs(), "{a} vs {b}");
    }
}
