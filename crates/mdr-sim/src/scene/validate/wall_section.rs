//! `[[walls]]`: every wall kind as solid pieces, and the initial overlaps of spheres and walls.

use super::*;
use crate::walls::Revolution;

impl Checker<'_, '_> {
    pub(super) fn wall(&mut self, table: &KeyPath, w: &WallSection, index: usize) -> Option<Wall> {
        let kind = format!("{:?}", w.kind).to_lowercase();
        let why = format!("by a wall of kind {kind}");
        let all = [
            ("point_m", w.point_m.is_some()),
            ("normal", w.normal.is_some()),
            ("min_m", w.min_m.is_some()),
            ("max_m", w.max_m.is_some()),
            ("open_top", w.open_top.is_some()),
            ("thickness_m", w.thickness_m.is_some()),
            ("center_m", w.center_m.is_some()),
            ("axis", w.axis.is_some()),
            ("radius_m", w.radius_m.is_some()),
            ("length_m", w.length_m.is_some()),
            ("capped", w.capped.is_some()),
            ("segments", w.segments.is_some()),
            ("outer_radius_m", w.outer_radius_m.is_some()),
            ("orifice_diameter_m", w.orifice_diameter_m.is_some()),
            ("file", w.file.is_some()),
            ("scale", w.scale.is_some()),
            ("offset_m", w.offset_m.is_some()),
            ("top_radius_m", w.top_radius_m.is_some()),
            ("exact_surface", w.exact_surface.is_some()),
        ];
        let used: &[&str] = match w.kind {
            WallKind::Plane => &["point_m", "normal"],
            WallKind::Box => &["min_m", "max_m", "open_top", "thickness_m"],
            WallKind::Cylinder => &[
                "center_m",
                "axis",
                "radius_m",
                "length_m",
                "capped",
                "segments",
                "thickness_m",
                "exact_surface",
            ],
            WallKind::Mesh => &["file", "scale", "offset_m"],
            WallKind::Cone => &[
                "center_m",
                "axis",
                "radius_m",
                "top_radius_m",
                "length_m",
                "segments",
                "thickness_m",
                "exact_surface",
            ],
            WallKind::OrificePlate => &[
                "center_m",
                "outer_radius_m",
                "orifice_diameter_m",
                "thickness_m",
                "segments",
                "exact_surface",
            ],
        };
        let unused: Vec<(&str, bool)> = all
            .iter()
            .filter(|(k, _)| !used.contains(k))
            .copied()
            .collect();
        self.unused(table, &unused, &why);
        let req = format!("required {why}");
        let vec_req = |c: &mut Self, key: &str, v: Option<[f64; 3]>| -> Option<Vector3<f64>> {
            let v = c.require(table, key, v, &req)?;
            c.vector(&table.key(key), v)
        };
        let pos_req = |c: &mut Self, key: &str, v: Option<f64>| -> Option<f64> {
            let v = c.require(table, key, v, &req)?;
            c.positive(&table.key(key), v)
        };
        let segments = match w.segments {
            Some(s) if !(3..=4096).contains(&s) => {
                self.error(
                    &table.key("segments"),
                    format!("= {s} is outside the allowed range [3, 4096]"),
                );
                return None;
            }
            Some(s) => s,
            None => 48,
        };
        let thickness = match w.thickness_m {
            Some(t) => Some(self.positive(&table.key("thickness_m"), t)?),
            None => None,
        };
        let exact = w.exact_surface.unwrap_or(false);
        let mut revolution = None;
        let pieces = match w.kind {
            WallKind::Plane => {
                let point = vec_req(self, "point_m", w.point_m);
                let normal = self
                    .require(table, "normal", w.normal, &req)
                    .and_then(|n| self.unit(&table.key("normal"), n));
                vec![WallPiece::HalfSpace {
                    point: point?,
                    normal: normal?,
                }]
            }
            WallKind::Box => {
                let (lo, hi) = (
                    vec_req(self, "min_m", w.min_m)?,
                    vec_req(self, "max_m", w.max_m)?,
                );
                if (0..3).any(|c| hi[c] <= lo[c]) {
                    self.error(&table.key("max_m"), "must exceed min_m in every component");
                    return None;
                }
                let t = thickness.unwrap_or_else(|| (hi - lo).min() / 10.0);
                walls::box_container(lo, hi, t, w.open_top.unwrap_or(true))
            }
            WallKind::Cylinder => {
                let center = vec_req(self, "center_m", w.center_m);
                let axis = match w.axis {
                    Some(a) => self.unit(&table.key("axis"), a),
                    None => Some(Vector3::z()),
                };
                let radius = pos_req(self, "radius_m", w.radius_m);
                let length = pos_req(self, "length_m", w.length_m);
                let (center, axis, radius, length) = (center?, axis?, radius?, length?);
                let capped = w.capped.unwrap_or(false);
                if exact {
                    revolution = Some(Revolution::cylinder(center, axis, radius, length, capped));
                }
                walls::cylinder_container(
                    center,
                    axis,
                    radius,
                    length,
                    thickness.unwrap_or(radius / 5.0),
                    segments,
                    capped,
                )
            }
            WallKind::Cone => {
                let center = vec_req(self, "center_m", w.center_m);
                let axis = match w.axis {
                    Some(a) => self.unit(&table.key("axis"), a),
                    None => Some(Vector3::z()),
                };
                let radius = pos_req(self, "radius_m", w.radius_m);
                let top = pos_req(self, "top_radius_m", w.top_radius_m);
                let length = pos_req(self, "length_m", w.length_m);
                let (center, axis, radius, top, length) = (center?, axis?, radius?, top?, length?);
                if exact {
                    revolution = Some(Revolution::cone(center, axis, radius, top, length));
                }
                walls::cone_container(
                    center,
                    axis,
                    radius,
                    top,
                    length,
                    thickness.unwrap_or(radius.max(top) / 10.0),
                    segments,
                )
            }
            WallKind::OrificePlate => {
                let center = vec_req(self, "center_m", w.center_m);
                let outer = pos_req(self, "outer_radius_m", w.outer_radius_m);
                let hole = pos_req(self, "orifice_diameter_m", w.orifice_diameter_m);
                let (center, outer, hole) = (center?, outer?, hole?);
                if hole / 2.0 >= outer {
                    self.error(
                        &table.key("orifice_diameter_m"),
                        format!("= {hole} must be smaller than the plate's diameter 2 × outer_radius_m = {}", 2.0 * outer),
                    );
                    return None;
                }
                let thickness = thickness.unwrap_or(outer / 10.0);
                if exact {
                    revolution = Some(Revolution::orifice_plate(center, outer, hole, thickness));
                }
                walls::orifice_plate(center, outer, hole, thickness, segments)
            }
            WallKind::Mesh => {
                let file = self.require(table, "file", w.file.as_deref(), &req)?;
                let path = self.read_file(&table.key("file"), file);
                let scale = match w.scale {
                    Some(s) => self.positive(&table.key("scale"), s)?,
                    None => 1.0,
                };
                let offset = match w.offset_m {
                    Some(o) => self.vector(&table.key("offset_m"), o)?,
                    None => Vector3::zeros(),
                };
                if !path.exists() {
                    return None;
                }
                match walls::read_mesh_with_notes(&path, scale, offset) {
                    Ok((piece, notes)) => {
                        for note in notes {
                            self.warn(&table.key("file"), note);
                        }
                        vec![piece]
                    }
                    Err(e) => {
                        self.error(&table.key("file"), e);
                        return None;
                    }
                }
            }
        };
        let angular_velocity = match w.angular_velocity_rad_per_s {
            Some(v) => Some(self.vector(&table.key("angular_velocity_rad_per_s"), v)?),
            None => None,
        };
        if w.rotation_center_m.is_some() && angular_velocity.is_none() {
            self.error(
                &table.key("rotation_center_m"),
                "is used only with angular_velocity_rad_per_s: remove it",
            );
        }
        if angular_velocity.is_some() && w.kind == WallKind::Plane {
            self.error(
                &table.key("angular_velocity_rad_per_s"),
                "a plane cannot rotate (use a box or a mesh)",
            );
            return None;
        }
        let removed_at = match w.removed_at_s {
            Some(t) => Some(self.non_negative(&table.key("removed_at_s"), t)?),
            None => None,
        };
        if removed_at.is_some() && angular_velocity.is_some() {
            self.error(
                &table.key("removed_at_s"),
                "a rotating wall cannot be removed: remove one of removed_at_s and angular_velocity_rad_per_s",
            );
            return None;
        }
        let origin = match w.rotation_center_m {
            Some(c) => self.vector(&table.key("rotation_center_m"), c)?,
            None => Vector3::zeros(),
        };
        // Pieces are stored relative to the wall body's origin.
        let pieces = pieces.into_iter().map(|p| p.translated(&-origin)).collect();
        let revolution = revolution.map(|r| Revolution {
            center: r.center - origin,
            ..r
        });
        Some(Wall {
            index,
            material: 0,
            pieces,
            origin,
            angular_velocity,
            removed_at,
            revolution,
        })
    }

    /// Refuse initial overlaps beyond each group's allowance (`max_initial_overlap_fraction`
    /// of the smaller radius, default [`OVERLAP_TOLERANCE`]; a pair of two groups gets the
    /// larger of their allowances).
    pub(super) fn check_overlaps(
        &mut self,
        root: &KeyPath,
        particles: &[ParticleInit],
        walls: &[Wall],
        allowance: &[f64],
    ) {
        let spheres: Vec<(Vector3<f64>, f64)> =
            particles.iter().map(|p| (p.position, p.radius)).collect();
        let tolerance =
            |p: &ParticleInit| allowance.get(p.group).copied().unwrap_or(OVERLAP_TOLERANCE);
        let smallest = particles
            .iter()
            .map(tolerance)
            .fold(f64::INFINITY, f64::min);
        let pairs = placement::overlapping_pairs(&spheres, smallest, usize::MAX);
        let mut reported = 0;
        for (i, j, overlap) in &pairs {
            let (a, b) = (&particles[*i], &particles[*j]);
            let allowed = tolerance(a).max(tolerance(b));
            if *overlap <= allowed * a.radius.min(b.radius) {
                continue;
            }
            self.error(
                &root.key("particles").index(b.group),
                format!(
                    "initial placement overlaps: particle {i} (group {}) and particle {j} (group {}) \
                     overlap by {overlap:.3e} m, more than {}% of the smaller radius \
                     (max_initial_overlap_fraction)",
                    a.group,
                    b.group,
                    allowed * 100.0
                ),
            );
            reported += 1;
            if reported >= 6 {
                break;
            }
        }
        let mut reported = 0;
        'walls: for wall in walls {
            for piece in &wall.pieces {
                let distance = piece.distance_fn();
                for (k, p) in particles.iter().enumerate() {
                    let d = distance(&(p.position - wall.origin));
                    if d < p.radius * (1.0 - tolerance(p)) {
                        self.error(
                            &root.key("walls").index(wall.index),
                            format!(
                                "initial placement: particle {k} (group {}, centre {:?} m, radius {:.3e} m) \
                                 overlaps this wall by {:.3e} m",
                                p.group,
                                p.position.as_slice(),
                                p.radius,
                                p.radius - d
                            ),
                        );
                        reported += 1;
                        if reported >= 6 {
                            break 'walls;
                        }
                        continue 'walls;
                    }
                }
            }
        }
    }
}

impl WallPiece {
    /// The same piece moved by `shift` (m).
    pub fn translated(self, shift: &Vector3<f64>) -> Self {
        match self {
            WallPiece::HalfSpace { point, normal } => WallPiece::HalfSpace {
                point: point + shift,
                normal,
            },
            WallPiece::Cuboid {
                center,
                rotation,
                half_extents,
            } => WallPiece::Cuboid {
                center: center + shift,
                rotation,
                half_extents,
            },
            WallPiece::ConvexHull { points } => WallPiece::ConvexHull {
                points: points.into_iter().map(|p| p + shift).collect(),
            },
            WallPiece::TriMesh {
                vertices,
                indices,
                closed,
            } => WallPiece::TriMesh {
                vertices: vertices.into_iter().map(|p| p + shift).collect(),
                indices,
                closed,
            },
        }
    }
}
