//! Reference coefficient of restitution of a head-on impact of two equal steel spheres (the
//! paper's values, Fig. 2), from mdr-contact's closed-form energy route (eq. 14, docs/theory.md §4):
//! the same `e_n` the single-impact validator gives, for the pair's `E*`, `R = r/2`, `m = m₁/2`;
//! with `wall` first, of a steel sphere on a steel half-space (the paper's Fig. 2 itself:
//! `R = r`, `m = m₁`); with `cylinder R_C` first, of a steel sphere on the inside of a steel
//! cylinder of radius `R_C` (the Hertz equivalent radius `R = √(r R″)`, `1/R″ = 1/r − 1/R_C`,
//! docs/lammps.md); with `sphere R_S` first, of a steel sphere on a steel sphere of radius `R_S`
//! that does not move (`R_S > 0`: from outside, `R = 1/(1/r + 1/R_S)`; `R_S < 0`: inside a
//! spherical shell of radius `|R_S|`, `R = 1/(1/r − 1/|R_S|)`).
//! With `radii R_A R_B` first, of a steel sphere on a steel wall of principal radii of curvature
//! `R_A`, `R_B` (0: flat in that direction, negative: concave; `R = √(R′ R″)`,
//! `1/R′ = 1/r + 1/R_A`, `1/R″ = 1/r + 1/R_B`, Johnson, *Contact Mechanics* §4.2).
//! Usage: `impact_reference [wall | cylinder R_C | sphere R_S | radii R_A R_B] RADIUS SPEED...`
//! (m, m/s); prints `speed e_n` lines.
//!
//! With `adhesive [wall] W E NU DENSITY QC THETA RADIUS SPEED...` first (J/m², Pa, -, kg/m³,
//! N/m, -, m, m/s): adhesive impacts of two equal spheres (or of a sphere on a half-space of its
//! own material) with Heß's rule on the MDR springs, from the single-impact validator's time
//! integration (`mdr_impact::Impact`, 200,000 steps per Hertz contact time: its time-step error
//! is far below LAMMPS's); prints `speed e_n stuck pull_off_force release_overlap` lines.
use mdr_contact::material::{ContactPair, Material};
use mdr_contact::normal::{MdrElastoPlastic, MdrState, NormalModel};
use mdr_impact::{Impact, NormalSpec};

/// `adhesive [wall] W E NU DENSITY QC THETA RADIUS SPEED...`.
fn adhesive(mut words: Vec<String>) -> Result<(), Box<dyn std::error::Error>> {
    let wall = words.first().is_some_and(|w| w == "wall");
    if wall {
        words.remove(0);
    }
    let args: Vec<f64> = words
        .iter()
        .map(|a| a.parse::<f64>())
        .collect::<Result<_, _>>()?;
    let [work, youngs, poisson, density, qc, theta, radius, speeds @ ..] = args.as_slice() else {
        return Err(
            "usage: impact_reference adhesive [wall] W E NU DENSITY QC THETA RADIUS SPEED..."
                .into(),
        );
    };
    let material = Material::new(*youngs, *poisson, *density)?;
    let pair = if wall {
        ContactPair::sphere_on_half_space(*radius, &material, &material)?
    } else {
        ContactPair::sphere_on_sphere(*radius, &material, *radius, &material)?
    };
    let params = MdrElastoPlastic::new(*qc, *theta)?;
    for v in speeds {
        let o = Impact::new(pair, NormalSpec::Mdr(params), *v)
            .work_of_adhesion(*work)
            .steps_per_contact(200_000)
            .run()?;
        println!(
            "{v} {:.12} {} {:.12e} {:.12e}",
            o.normal_restitution, o.stuck as i32, o.pull_off_force, o.release_overlap
        );
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut words: Vec<String> = std::env::args().skip(1).collect();
    if words.first().is_some_and(|w| w == "adhesive") {
        words.remove(0);
        return adhesive(words);
    }
    let wall = words.first().is_some_and(|w| w == "wall");
    if wall {
        words.remove(0);
    }
    let cylinder = if words.first().is_some_and(|w| w == "cylinder") {
        words.remove(0);
        Some(words.remove(0).parse::<f64>()?)
    } else {
        None
    };
    let sphere = if words.first().is_some_and(|w| w == "sphere") {
        words.remove(0);
        Some(words.remove(0).parse::<f64>()?)
    } else {
        None
    };
    let radii = if words.first().is_some_and(|w| w == "radii") {
        words.remove(0);
        let r_a = words.remove(0).parse::<f64>()?;
        Some((r_a, words.remove(0).parse::<f64>()?))
    } else {
        None
    };
    let args: Vec<f64> = words
        .iter()
        .map(|a| a.parse::<f64>())
        .collect::<Result<_, _>>()?;
    let (radius, speeds) = args
        .split_first()
        .ok_or("usage: impact_reference [wall] RADIUS SPEED...")?;
    let steel = Material::paper_steel();
    let pair = if let Some(rc) = cylinder {
        let flat = ContactPair::sphere_on_half_space(*radius, &steel, &steel)?;
        let around = 1.0 / (1.0 / radius - 1.0 / rc);
        ContactPair::new(
            flat.effective_modulus(),
            flat.effective_shear_modulus(),
            (radius * around).sqrt(),
            flat.reduced_mass(),
        )?
    } else if let Some(rs) = sphere {
        // both principal directions curved alike: R' = R'' (Johnson §4.2)
        let flat = ContactPair::sphere_on_half_space(*radius, &steel, &steel)?;
        ContactPair::new(
            flat.effective_modulus(),
            flat.effective_shear_modulus(),
            1.0 / (1.0 / radius + 1.0 / rs),
            flat.reduced_mass(),
        )?
    } else if let Some((r_a, r_b)) = radii {
        let flat = ContactPair::sphere_on_half_space(*radius, &steel, &steel)?;
        let along = |r_wall: f64| {
            if r_wall == 0.0 {
                *radius
            } else {
                1.0 / (1.0 / radius + 1.0 / r_wall)
            }
        };
        ContactPair::new(
            flat.effective_modulus(),
            flat.effective_shear_modulus(),
            (along(r_a) * along(r_b)).sqrt(),
            flat.reduced_mass(),
        )?
    } else if wall {
        ContactPair::sphere_on_half_space(*radius, &steel, &steel)?
    } else {
        ContactPair::sphere_on_sphere(*radius, &steel, *radius, &steel)?
    };
    let law = MdrElastoPlastic::paper().bind(&pair)?;
    for v in speeds {
        let e = law
            .impact(&MdrState::default(), pair.reduced_mass(), *v)?
            .restitution;
        println!("{v} {e:.12}");
    }
    Ok(())
}
