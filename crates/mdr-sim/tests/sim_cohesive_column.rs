//! The cohesive column: a column of spheres with a work of adhesion collapses less the larger
//! its Bond number `Bo = F_c / (m g)` (JKR pull-off of two spheres over one's weight): the
//! run-out shrinks and the deposit stays taller, as in the discrete and continuum simulations of
//! Abramian, Staron & Lagrée (J. Rheol. 64, 1227, 2020), whose cohesive columns spread less with
//! growing cohesion until, above a critical cohesion, they do not collapse. Without adhesion
//! (`Bo = 0`, the negative control) the column spreads most.

mod common;

use mdr_sim::{run_scene, scene::validate::parse_scene, RunOptions};

/// `(Bond number, normalised run-out (R − R0)/R0, final height / H0)` of an `n × n × layers`
/// column with the work of adhesion `gamma` (J/m²) run for `duration` (s).
fn collapse(n: usize, layers: usize, duration: f64, gamma: f64) -> (f64, f64, f64) {
    let dir = common::temp_dir("cohesive-column");
    let text = common::column(n, layers, duration, 0.5, "").replacen(
        "density_kg_per_m3 = 2500.0\n",
        &format!("density_kg_per_m3 = 2500.0\nwork_of_adhesion_j_per_m2 = {gamma:e}\n"),
        1,
    );
    let path = common::write(&dir, "column.toml", &text);
    let scene = parse_scene(&path, &text).unwrap_or_else(|e| panic!("{e}"));
    let summary = run_scene(
        &scene,
        &RunOptions::new(dir.join("out")).quiet(true).no_frames(true),
    )
    .expect("run");
    let h = &summary.headline;
    let bo = h.get("bond_number").unwrap_or(0.0);
    let spread = h.get("normalised_runout").unwrap();
    let height = h.get("final_height_m").unwrap() / h.get("initial_height_m").unwrap();
    eprintln!("Δγ = {gamma} J/m²: Bo = {bo:.2}, (R − R0)/R0 = {spread:.3}, H/H0 = {height:.3}");
    (bo, spread, height)
}

/// Short version (CI): a 4 × 4 × 8 column at `Bo = 0, 11, 29`: the run-out falls and the
/// final height rises with `Bo`, and the strongest cohesion at least halves the spread.
#[test]
fn cohesive_column_spreads_less_as_the_bond_number_grows() {
    check(4, 8, 0.15, &[0.0, 2.0, 5.0]);
}

/// Long version: a 6 × 6 × 14 column over four Bond numbers.
#[test]
#[ignore = "long: a 6 × 6 × 14 column at four Bond numbers"]
fn cohesive_column_spreads_less_as_the_bond_number_grows_long() {
    check(6, 14, 0.3, &[0.0, 0.2, 1.0, 5.0]);
}

fn check(n: usize, layers: usize, duration: f64, gammas: &[f64]) {
    let runs: Vec<(f64, f64, f64)> = gammas
        .iter()
        .map(|&g| collapse(n, layers, duration, g))
        .collect();
    assert_eq!(runs[0].0, 0.0, "no adhesion, no Bond number");
    for w in runs.windows(2) {
        assert!(w[1].0 > w[0].0, "Bond numbers {runs:?}");
        assert!(w[1].1 < w[0].1, "run-out did not fall with Bo: {runs:?}");
        assert!(w[1].2 >= w[0].2, "height did not rise with Bo: {runs:?}");
    }
    let (first, last) = (runs[0], runs[runs.len() - 1]);
    assert!(
        first.1 > 0.2,
        "the cohesionless column barely spread: {runs:?}"
    );
    assert!(last.1 < 0.5 * first.1, "cohesion barely mattered: {runs:?}");
}
