//! Reference coefficient of restitution of a head-on impact of two equal steel spheres (the
//! paper's values, Fig. 2), from mdr-contact's closed-form energy route (eq. 14, docs/theory.md §4):
//! the same `e_n` the single-impact validator gives, for the pair's `E*`, `R = r/2`, `m = m₁/2`;
//! with `wall` first, of a steel sphere on a steel half-space (the paper's Fig. 2 itself:
//! `R = r`, `m = m₁`); with `cylinder R_C` first, of a steel sphere on the inside of a steel
//! cylinder of radius `R_C` (the Hertz equivalent radius `R = √(r R″)`, `1/R″ = 1/r − 1/R_C`,
//! docs/lammps.md).
//! Usage: `impact_reference [wall | cylinder R_C] RADIUS SPEED...` (m, m/s); prints `speed e_n`
//! lines.
use mdr_contact::material::{ContactPair, Material};
use mdr_contact::normal::{MdrElastoPlastic, MdrState, NormalModel};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut words: Vec<String> = std::env::args().skip(1).collect();
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
