//! The work of adhesion of a scene's contacts: per material (`[[material]]
//! work_of_adhesion_j_per_m2`, `Δγ_i`, default 0), mixed per pair by the geometric mean
//! `Δγ_ij = √(Δγ_i Δγ_j)` (docs/theory.md §9, "Pair mixing"). A scene whose materials give
//! adhesion runs the adhesive MDR law (`adhesive_mdr`) in place of `normal = "mdr"`, bound per
//! material pair with that pair's `Δγ_ij` (a pair with `Δγ_ij = 0` runs the MDR law's result
//! exactly), in force mode on both paths and in restitution mode alike.

use super::*;

impl Checker<'_, '_> {
    /// The materials' `Δγ_i` (J/m²; 0 where not given), each checked (finite, ≥ 0).
    pub(super) fn works_of_adhesion(&mut self, file: &SceneFile) -> Vec<f64> {
        let root = KeyPath::root();
        file.material
            .iter()
            .enumerate()
            .map(|(i, m)| match m.work_of_adhesion_j_per_m2 {
                Some(w) => {
                    let path = root
                        .key("material")
                        .index(i)
                        .key("work_of_adhesion_j_per_m2");
                    if w.is_finite() && w >= 0.0 {
                        w
                    } else {
                        self.error(
                            &path,
                            format!("= {w} J/m² is outside the allowed range [0, inf) J/m²"),
                        );
                        0.0
                    }
                }
                None => 0.0,
            })
            .collect()
    }

    /// Replace the scene's `mdr` law by the adhesive MDR law when its materials give adhesion:
    /// `gammas` per material, the spheres and walls that meet.
    pub(super) fn adhesion(
        &mut self,
        gammas: &[f64],
        particles: &[ParticleInit],
        walls: &[Wall],
        contact: &mut ContactSpec,
    ) {
        let Some(first) = gammas.iter().position(|&g| g > 0.0) else {
            return;
        };
        let key = KeyPath::root()
            .key("material")
            .index(first)
            .key("work_of_adhesion_j_per_m2");
        if contact.normal.law != MdrElastoPlastic::DECLARATION.name {
            let message = if contact.normal.law == AdhesiveMdr::DECLARATION.name {
                "is given per material while [contact] normal = \"adhesive_mdr\" sets one \
                 `work_of_adhesion_j_per_m2` for every pair: give it in one place (per material \
                 with normal = \"mdr\", or in [contact])"
                    .to_owned()
            } else {
                format!(
                    "needs normal = \"mdr\" (the adhesive MDR law runs then); normal = \"{}\" \
                     has no adhesion",
                    contact.normal.law
                )
            };
            self.error(&key, message);
            return;
        }
        // Every material pair that can meet: sphere–sphere (a material with itself only when
        // it has two spheres), sphere–wall.
        let mut count = vec![0_usize; gammas.len()];
        for p in particles {
            count[p.material] += 1;
        }
        let mut pairs: Vec<(usize, usize, f64)> = Vec::new();
        let mut meet = |a: usize, b: usize| {
            let (a, b) = (a.min(b), a.max(b));
            if !pairs.iter().any(|&(x, y, _)| (x, y) == (a, b)) {
                pairs.push((a, b, mixed_work_of_adhesion(gammas[a], gammas[b])));
            }
        };
        for a in (0..gammas.len()).filter(|&a| count[a] > 0) {
            for b in (a..gammas.len()).filter(|&b| count[b] > 0) {
                if a != b || count[a] > 1 {
                    meet(a, b);
                }
            }
            for w in walls {
                meet(a, w.material);
            }
        }
        let hi = pairs.iter().fold(0.0_f64, |hi, p| hi.max(p.2));
        if hi == 0.0 {
            return;
        }
        // The scene's law carries the largest value of the pairs that meet; each material pair
        // is bound with its own.
        let values = vec![contact.normal.values[0], contact.normal.values[1], hi];
        match AdhesiveMdr::from_values(&values) {
            Ok(_) => {
                contact.normal = NormalSpec {
                    law: AdhesiveMdr::DECLARATION.name,
                    values,
                };
                contact.works_of_adhesion = gammas.to_vec();
            }
            Err(e) => self.error(&key, e.to_string()),
        }
    }
}

/// The work of adhesion of a pair of materials with works of adhesion `a` and `b` against
/// themselves (J/m²): `√(a b)`, the Berthelot–Fowkes rule for dispersion forces (docs/theory.md
/// §9, "Pair mixing"; LAMMPS `pair granular` mixes the `jkr`/`dmt` cohesion alike).
pub fn mixed_work_of_adhesion(a: f64, b: f64) -> f64 {
    if a == b {
        a
    } else {
        (a * b).sqrt()
    }
}
