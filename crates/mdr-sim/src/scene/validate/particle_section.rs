//! `[[particles]]`: placements (lattice, random, CSV, LAMMPS data), size distributions and
//! radius classes.

use super::*;

/// Sphere radii from this size up (m) get the millimetre hint.
const MILLIMETRE_HINT_RADIUS_M: f64 = 1.0;

impl Checker<'_, '_> {
    pub(super) fn place_group(
        &mut self,
        table: &KeyPath,
        g: &ParticleGroup,
        rng: &mut ChaCha8Rng,
        total: &mut u64,
    ) -> Option<Vec<placement::ReadSphere>> {
        let is_file = matches!(g.placement, PlacementKind::Csv | PlacementKind::Lammps);
        let count = match g.count {
            Some(0) => {
                self.error(
                    &table.key("count"),
                    "= 0 is outside the allowed range [1, 1000000]: a group needs particles",
                );
                None
            }
            Some(n) if n > MAX_PARTICLES || total.saturating_add(n) > MAX_PARTICLES => {
                self.error(
                    &table.key("count"),
                    format!("= {n} is outside the allowed range [1, {MAX_PARTICLES}] (whole scene at most {MAX_PARTICLES})"),
                );
                None
            }
            Some(n) => Some(n),
            // A file without `count`: every sphere of it, within what the scene has room for.
            None if is_file => Some(MAX_PARTICLES.saturating_sub(*total)),
            None => {
                self.error(
                    table,
                    "missing key `count` (required by placement = \"lattice\" / \"random\")",
                );
                None
            }
        };
        let law = if is_file {
            self.unused(
                table,
                &[
                    ("radius_m", g.radius_m.is_some()),
                    ("size_distribution", g.size_distribution.is_some()),
                    ("radius_min_m", g.radius_min_m.is_some()),
                    ("radius_max_m", g.radius_max_m.is_some()),
                    ("radius_std_m", g.radius_std_m.is_some()),
                    ("region_min_m", g.region_min_m.is_some()),
                    ("region_max_m", g.region_max_m.is_some()),
                    ("gap_fraction", g.gap_fraction.is_some()),
                    ("jitter_fraction", g.jitter_fraction.is_some()),
                ],
                "when the particles are read from a file (radii and positions come from it)",
            );
            None
        } else {
            self.unused(
                table,
                &[
                    ("file", g.file.is_some()),
                    ("length_scale_m", g.length_scale_m.is_some()),
                ],
                "by placement = \"lattice\" / \"random\"",
            );
            let law = self.radius_law(table, g);
            if let Some(law) = &law {
                self.millimetre_hint(table, g, law.max());
            }
            law
        };
        let mut out = None;
        match g.placement {
            PlacementKind::Lattice | PlacementKind::Random => {
                if g.placement == PlacementKind::Random {
                    self.unused(
                        table,
                        &[
                            ("gap_fraction", g.gap_fraction.is_some()),
                            ("jitter_fraction", g.jitter_fraction.is_some()),
                        ],
                        "by placement = \"random\"",
                    );
                }
                let lo = self
                    .require(
                        table,
                        "region_min_m",
                        g.region_min_m,
                        "required by lattice/random placement",
                    )
                    .and_then(|v| self.vector(&table.key("region_min_m"), v));
                let hi = self
                    .require(
                        table,
                        "region_max_m",
                        g.region_max_m,
                        "required by lattice/random placement",
                    )
                    .and_then(|v| self.vector(&table.key("region_max_m"), v));
                if let (Some(lo), Some(hi)) = (lo, hi) {
                    if (0..3).any(|c| hi[c] <= lo[c]) {
                        self.error(
                            &table.key("region_max_m"),
                            format!(
                                "must exceed region_min_m in every component ({lo:?} vs {hi:?})"
                            ),
                        );
                        return None;
                    }
                }
                let gap = g.gap_fraction.map_or(Some(0.01), |v| {
                    self.non_negative(&table.key("gap_fraction"), v)
                });
                let jitter = match g.jitter_fraction {
                    Some(v) => {
                        let v = self.non_negative(&table.key("jitter_fraction"), v);
                        if v.is_some_and(|v| v > 1.0) {
                            self.error(
                                &table.key("jitter_fraction"),
                                "is outside the allowed range [0, 1]",
                            );
                            None
                        } else {
                            v
                        }
                    }
                    None => Some(0.0),
                };
                let (Some(lo), Some(hi), Some(law), Some(count), Some(gap), Some(jitter)) =
                    (lo, hi, law, count, gap, jitter)
                else {
                    return None;
                };
                let placed = if g.placement == PlacementKind::Lattice {
                    placement::lattice(lo, hi, &law, count as usize, gap, jitter, rng)
                } else {
                    placement::random_fill(lo, hi, &law, count as usize, rng)
                };
                match placed {
                    Ok(p) => {
                        out = Some(p.into_iter().map(|(p, r)| (p, r, None)).collect::<Vec<_>>())
                    }
                    Err(e) => self.error(&table.key("count"), e),
                }
            }
            PlacementKind::Csv | PlacementKind::Lammps => {
                let file = self.require(
                    table,
                    "file",
                    g.file.as_deref(),
                    "required when reading particles from a file",
                )?;
                let path = self.read_file(&table.key("file"), file);
                if !path.exists() {
                    return None;
                }
                let read = if g.placement == PlacementKind::Csv {
                    self.unused(
                        table,
                        &[("length_scale_m", g.length_scale_m.is_some())],
                        "by placement = \"csv\" (the CSV is in metres)",
                    );
                    placement::read_csv(&path, MAX_PARTICLES as usize)
                } else {
                    let scale = match g.length_scale_m {
                        Some(s) => self.positive(&table.key("length_scale_m"), s)?,
                        None => 1.0,
                    };
                    placement::read_lammps(&path, scale, MAX_PARTICLES as usize)
                        .map(|v| v.into_iter().map(|(p, r)| (p, r, None)).collect())
                };
                match read {
                    Ok(mut p) => {
                        if p.is_empty() {
                            self.error(&table.key("file"), "the file holds no particles");
                            return None;
                        }
                        let limit = count.unwrap_or(MAX_PARTICLES) as usize;
                        if p.len() > limit {
                            if g.count.is_none() {
                                self.error(
                                    &table.key("file"),
                                    format!("the file holds {} particles, more than the allowed {limit} (whole scene at most {MAX_PARTICLES})", p.len()),
                                );
                                return None;
                            }
                            p.truncate(limit);
                        }
                        out = Some(p);
                    }
                    Err(e) => self.error(&table.key("file"), e),
                }
            }
        }
        if let Some(p) = &out {
            *total = total.saturating_add(p.len() as u64);
        }
        out
    }

    /// `region_radius_m`: the placed spheres within that distance of the region's central line
    /// parallel to z; an error when the key does not apply or nothing is left.
    pub(super) fn trim_to_cylinder(
        &mut self,
        table: &KeyPath,
        g: &ParticleGroup,
        placed: Option<Vec<placement::ReadSphere>>,
    ) -> Option<Vec<placement::ReadSphere>> {
        let Some(radius) = g.region_radius_m else {
            return placed;
        };
        let key = table.key("region_radius_m");
        if !matches!(g.placement, PlacementKind::Lattice | PlacementKind::Random) {
            self.error(
                &key,
                "is used only with placement = \"lattice\" or \"random\": remove it",
            );
            return None;
        }
        let radius = self.positive(&key, radius)?;
        let (lo, hi) = (g.region_min_m?, g.region_max_m?);
        let (cx, cy) = (0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]));
        let kept: Vec<_> = placed?
            .into_iter()
            .filter(|(p, _, _)| (p.x - cx).hypot(p.y - cy) <= radius)
            .collect();
        if kept.is_empty() {
            self.error(
                &key,
                format!("= {radius} m leaves no sphere of the group in the region"),
            );
            return None;
        }
        Some(kept)
    }

    /// `radius_classes`: `Some(None)` when absent, `Some(Some((radius_min_m, class width)))` when
    /// valid, `None` after an error.
    pub(super) fn radius_classes(
        &mut self,
        table: &KeyPath,
        g: &ParticleGroup,
    ) -> Option<Option<(f64, f64)>> {
        let Some(n) = g.radius_classes else {
            return Some(None);
        };
        let key = table.key("radius_classes");
        if !matches!(
            g.size_distribution,
            Some(SizeDistribution::Uniform | SizeDistribution::Normal)
        ) {
            self.error(
                &key,
                "is used only with size_distribution = \"uniform\" or \"normal\": remove it",
            );
            return None;
        }
        if !(2..=255).contains(&n) {
            self.error(&key, format!("= {n} is outside the allowed range [2, 255]"));
            return None;
        }
        match (g.radius_min_m, g.radius_max_m) {
            (Some(lo), Some(hi)) if lo.is_finite() && hi.is_finite() && hi > lo => {
                Some(Some((lo, (hi - lo) / n as f64)))
            }
            // radius_law takes equal positive bounds (one radius), which have no classes; it
            // reports the others.
            (Some(lo), Some(hi)) if hi == lo && lo > 0.0 && lo.is_finite() => {
                self.error(
                    &key,
                    format!(
                        "= {n} needs radius_max_m > radius_min_m (both are {lo} m: one radius): \
                         remove it"
                    ),
                );
                None
            }
            // radius_law reports the bounds' own problems.
            _ => None,
        }
    }

    /// A sphere radius of a metre or more is most often a radius in millimetres written into a
    /// key in metres: a warning at the radius key says so.
    fn millimetre_hint(&mut self, table: &KeyPath, g: &ParticleGroup, largest: f64) {
        if largest < MILLIMETRE_HINT_RADIUS_M {
            return;
        }
        let key = if g.radius_m.is_some() {
            "radius_m"
        } else {
            "radius_max_m"
        };
        self.warn(
            &table.key(key),
            format!(
                "= {largest} m: spheres of a metre or more? Every length of a scene is in metres (the \
                 `_m` keys); if this is millimetres, write {:e}",
                largest / 1000.0
            ),
        );
    }

    pub(super) fn radius_law(&mut self, table: &KeyPath, g: &ParticleGroup) -> Option<RadiusLaw> {
        let dist = g.size_distribution.unwrap_or(SizeDistribution::Mono);
        let pos = |c: &mut Self, key: &str, v: Option<f64>, why: &str| -> Option<f64> {
            let v = c.require(table, key, v, why)?;
            c.positive(&table.key(key), v)
        };
        match dist {
            SizeDistribution::Mono => {
                self.unused(
                    table,
                    &[
                        ("radius_min_m", g.radius_min_m.is_some()),
                        ("radius_max_m", g.radius_max_m.is_some()),
                        ("radius_std_m", g.radius_std_m.is_some()),
                    ],
                    "by size_distribution = \"mono\"",
                );
                pos(
                    self,
                    "radius_m",
                    g.radius_m,
                    "required by size_distribution = \"mono\"",
                )
                .map(RadiusLaw::Mono)
            }
            SizeDistribution::Uniform => {
                self.unused(
                    table,
                    &[
                        ("radius_m", g.radius_m.is_some()),
                        ("radius_std_m", g.radius_std_m.is_some()),
                    ],
                    "by size_distribution = \"uniform\"",
                );
                let min = pos(
                    self,
                    "radius_min_m",
                    g.radius_min_m,
                    "required by size_distribution = \"uniform\"",
                );
                let max = pos(
                    self,
                    "radius_max_m",
                    g.radius_max_m,
                    "required by size_distribution = \"uniform\"",
                );
                let (min, max) = (min?, max?);
                if max < min {
                    self.error(
                        &table.key("radius_max_m"),
                        format!("= {max} must be ≥ radius_min_m = {min}"),
                    );
                    return None;
                }
                Some(RadiusLaw::Uniform { min, max })
            }
            SizeDistribution::Normal => {
                let why = "required by size_distribution = \"normal\"";
                let mean = pos(self, "radius_m", g.radius_m, why);
                let std = pos(self, "radius_std_m", g.radius_std_m, why);
                let min = pos(self, "radius_min_m", g.radius_min_m, why);
                let max = pos(self, "radius_max_m", g.radius_max_m, why);
                let (mean, std, min, max) = (mean?, std?, min?, max?);
                if !(min <= mean && mean <= max) {
                    self.error(
                        &table.key("radius_m"),
                        format!(
                            "= {mean} must lie in [radius_min_m, radius_max_m] = [{min}, {max}]"
                        ),
                    );
                    return None;
                }
                Some(RadiusLaw::Normal {
                    mean,
                    std,
                    min,
                    max,
                })
            }
        }
    }
}
