//! Initial particle placement: lattice, random non-overlapping fill (seeded), or read from a CSV
//! or LAMMPS data file; and the overlap check every placement goes through.

use nalgebra::Vector3;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::collections::HashMap;
use std::path::Path;

/// One sphere to create.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParticleInit {
    /// Centre (m).
    pub position: Vector3<f64>,
    /// Radius (m).
    pub radius: f64,
    /// Initial velocity (m/s).
    pub velocity: Vector3<f64>,
    /// Material index into the scene's materials.
    pub material: usize,
    /// Index of the `[[particles]]` group.
    pub group: usize,
}

/// Radii drawn from a distribution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RadiusLaw {
    /// All equal.
    Mono(f64),
    /// Uniform in `[min, max]`.
    Uniform {
        /// Smallest (m).
        min: f64,
        /// Largest (m).
        max: f64,
    },
    /// Normal, truncated to `[min, max]` by redrawing.
    Normal {
        /// Mean (m).
        mean: f64,
        /// Standard deviation (m).
        std: f64,
        /// Smallest (m).
        min: f64,
        /// Largest (m).
        max: f64,
    },
}

impl RadiusLaw {
    /// Largest radius the law can produce (m).
    pub fn max(&self) -> f64 {
        match *self {
            RadiusLaw::Mono(r) => r,
            RadiusLaw::Uniform { max, .. } | RadiusLaw::Normal { max, .. } => max,
        }
    }

    /// Smallest radius the law can produce (m).
    pub fn min(&self) -> f64 {
        match *self {
            RadiusLaw::Mono(r) => r,
            RadiusLaw::Uniform { min, .. } | RadiusLaw::Normal { min, .. } => min,
        }
    }

    /// Draw one radius.
    pub fn draw(&self, rng: &mut ChaCha8Rng) -> f64 {
        match *self {
            RadiusLaw::Mono(r) => r,
            RadiusLaw::Uniform { min, max } => {
                if max > min {
                    rng.random_range(min..=max)
                } else {
                    min
                }
            }
            RadiusLaw::Normal {
                mean,
                std,
                min,
                max,
            } => {
                // Box–Muller; redraw outside [min, max] (bounded: fall back to the mean).
                for _ in 0..64 {
                    let u1: f64 = rng.random::<f64>().max(f64::MIN_POSITIVE);
                    let u2: f64 = rng.random();
                    let z = (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos();
                    let r = mean + std * z;
                    if (min..=max).contains(&r) {
                        return r;
                    }
                }
                mean.clamp(min, max)
            }
        }
    }
}

/// Simple cubic lattice in `[lo, hi]` with spacing `2 r_max (1 + gap)`, at most `count` sites,
/// filled bottom layer first; each centre jittered by up to `jitter` × the gap.
pub fn lattice(
    lo: Vector3<f64>,
    hi: Vector3<f64>,
    law: &RadiusLaw,
    count: usize,
    gap: f64,
    jitter: f64,
    rng: &mut ChaCha8Rng,
) -> Result<Vec<(Vector3<f64>, f64)>, String> {
    let r = law.max();
    let spacing = 2.0 * r * (1.0 + gap);
    let fit = |axis: usize| -> usize {
        let room = hi[axis] - lo[axis] - 2.0 * r;
        if room < 0.0 {
            0
        } else {
            // Saturating: a huge region must not overflow (the count limit applies anyway).
            ((room / spacing).floor() as usize).saturating_add(1)
        }
    };
    let (nx, ny, nz) = (fit(0), fit(1), fit(2));
    let capacity = nx.saturating_mul(ny).saturating_mul(nz);
    if capacity < count {
        return Err(format!(
            "the region holds only {capacity} lattice sites ({nx} × {ny} × {nz} at spacing {spacing:.4e} m) \
             for {count} particles: enlarge the region or reduce count{}",
            if nx.min(ny).min(nz) == 0 {
                format!(
                    " (a sphere of diameter {:.4e} m does not fit the region at all: the radius and \
                     the region are both in metres)",
                    2.0 * r
                )
            } else {
                String::new()
            }
        ));
    }
    let slack = spacing - 2.0 * r;
    let mut out = Vec::with_capacity(count);
    'fill: for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                if out.len() == count {
                    break 'fill;
                }
                let mut p = lo
                    + Vector3::new(
                        r + i as f64 * spacing,
                        r + j as f64 * spacing,
                        r + k as f64 * spacing,
                    );
                if jitter > 0.0 {
                    let amp = 0.5 * jitter * slack;
                    for c in 0..3 {
                        // Stay inside the region: the region's faces are often walls.
                        p[c] = (p[c] + rng.random_range(-amp..=amp)).clamp(lo[c] + r, hi[c] - r);
                    }
                }
                out.push((p, law.draw(rng)));
            }
        }
    }
    Ok(out)
}

/// Random non-overlapping fill of `[lo, hi]` with `count` spheres (random sequential addition),
/// giving up after `50 × count` attempts.
pub fn random_fill(
    lo: Vector3<f64>,
    hi: Vector3<f64>,
    law: &RadiusLaw,
    count: usize,
    rng: &mut ChaCha8Rng,
) -> Result<Vec<(Vector3<f64>, f64)>, String> {
    let r_max = law.max();
    let mut grid = Grid::new(2.0 * r_max);
    let mut out: Vec<(Vector3<f64>, f64)> = Vec::with_capacity(count);
    let attempts = 50usize.saturating_mul(count).max(1000);
    let mut tries = 0usize;
    while out.len() < count {
        tries += 1;
        if tries > attempts {
            let volume: f64 = out
                .iter()
                .map(|(_, r)| 4.0 / 3.0 * std::f64::consts::PI * r.powi(3))
                .sum();
            let region = (hi - lo).product();
            return Err(format!(
                "random fill placed only {} of {count} particles after {attempts} attempts \
                 (solid fraction reached {:.2}; random sequential addition stalls near 0.38): \
                 enlarge the region, reduce count, or use placement = \"lattice\"",
                out.len(),
                volume / region
            ));
        }
        let radius = law.draw(rng);
        let mut p = Vector3::zeros();
        let mut fits = true;
        for c in 0..3 {
            let (a, b) = (lo[c] + radius, hi[c] - radius);
            if b < a {
                fits = false;
                break;
            }
            p[c] = if b > a { rng.random_range(a..=b) } else { a };
        }
        if !fits {
            continue;
        }
        if grid
            .neighbours(&p)
            .any(|i| (out[i].0 - p).norm() < out[i].1 + radius)
        {
            continue;
        }
        grid.insert(&p, out.len());
        out.push((p, radius));
    }
    Ok(out)
}

/// A sphere read from a file: centre (m), radius (m), optional velocity (m/s).
pub type ReadSphere = (Vector3<f64>, f64, Option<Vector3<f64>>);

/// Read `x_m,y_m,z_m,radius_m[,vx_m_per_s,vy_m_per_s,vz_m_per_s]` rows (header required). A file
/// of more than `max_rows` rows is refused when its next row is reached, so no more than
/// `max_rows` spheres are ever held.
pub fn read_csv(path: &Path, max_rows: usize) -> Result<Vec<ReadSphere>, String> {
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .from_path(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let headers = reader
        .headers()
        .map_err(|e| format!("{}: {e}", path.display()))?
        .clone();
    let col = |name: &str| headers.iter().position(|h| h == name);
    let (Some(ix), Some(iy), Some(iz), Some(ir)) =
        (col("x_m"), col("y_m"), col("z_m"), col("radius_m"))
    else {
        return Err(format!(
            "{}: the header must name the columns x_m, y_m, z_m, radius_m (found: {})",
            path.display(),
            headers.iter().collect::<Vec<_>>().join(", ")
        ));
    };
    let vel = match (col("vx_m_per_s"), col("vy_m_per_s"), col("vz_m_per_s")) {
        (Some(a), Some(b), Some(c)) => Some([a, b, c]),
        _ => None,
    };
    let mut out = Vec::new();
    for (row, record) in reader.records().enumerate() {
        if row == max_rows {
            return Err(format!(
                "{}: more than {max_rows} particles, the most a scene holds",
                path.display()
            ));
        }
        let record = record.map_err(|e| format!("{}: {e}", path.display()))?;
        let line = record.position().map_or(row + 2, |p| p.line() as usize);
        let num = |i: usize, name: &str| -> Result<f64, String> {
            let s = record.get(i).unwrap_or("");
            let v: f64 = s.parse().map_err(|_| {
                format!(
                    "{}:{line}: `{name}` = `{s}` is not a number",
                    path.display()
                )
            })?;
            if v.is_finite() {
                Ok(v)
            } else {
                Err(format!(
                    "{}:{line}: `{name}` = {v} is not finite",
                    path.display()
                ))
            }
        };
        let p = Vector3::new(num(ix, "x_m")?, num(iy, "y_m")?, num(iz, "z_m")?);
        let r = num(ir, "radius_m")?;
        if r <= 0.0 {
            return Err(format!(
                "{}:{line}: `radius_m` = {r} is outside the allowed range (0, inf)",
                path.display()
            ));
        }
        let v = match vel {
            Some([a, b, c]) => Some(Vector3::new(
                num(a, "vx_m_per_s")?,
                num(b, "vy_m_per_s")?,
                num(c, "vz_m_per_s")?,
            )),
            None => None,
        };
        out.push((p, r, v));
    }
    Ok(out)
}

/// Read the `Atoms # sphere` section of a LAMMPS data file (`id type diameter density x y z
/// [ix iy iz]`), scaling lengths by `length_scale` (m per LAMMPS length unit). Atoms are sorted by
/// id so the order does not depend on how LAMMPS wrote them. A file that declares more than
/// `max_atoms` atoms is refused before they are read; the file is read line by line.
pub fn read_lammps(
    path: &Path,
    length_scale: f64,
    max_atoms: usize,
) -> Result<Vec<(Vector3<f64>, f64)>, String> {
    let file =
        std::fs::File::open(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let mut lines = std::io::BufRead::lines(std::io::BufReader::new(file))
        .enumerate()
        .map(|(i, line)| {
            line.map(|l| (i, l))
                .map_err(|e| format!("{}:{}: {e}", path.display(), i + 1))
        });
    let mut declared: Option<usize> = None;
    for line in lines.by_ref() {
        let (_, line) = line?;
        let t = line.trim();
        if let Some(n) = t.strip_suffix("atoms") {
            declared = n.trim().parse().ok();
        }
        if t.starts_with("Atoms") {
            if !t.contains("sphere") && t.contains('#') {
                return Err(format!(
                    "{}: only `Atoms # sphere` sections are supported (found `{t}`)",
                    path.display()
                ));
            }
            break;
        }
    }
    let Some(n) = declared else {
        return Err(format!(
            "{}: no `N atoms` line before the Atoms section",
            path.display()
        ));
    };
    if n > max_atoms {
        return Err(format!(
            "{}: the header declares {n} atoms, more than {max_atoms}, the most a scene holds",
            path.display()
        ));
    }
    let mut atoms: Vec<(u64, Vector3<f64>, f64)> = Vec::with_capacity(n);
    for line in lines {
        let (i, line) = line?;
        let t = line.split('#').next().unwrap_or("").trim();
        if t.is_empty() {
            if atoms.is_empty() {
                continue;
            }
            break;
        }
        let f: Vec<&str> = t.split_whitespace().collect();
        if f.len() < 7 {
            break; // next section header
        }
        let num = |k: usize| -> Result<f64, String> {
            f[k].parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    format!(
                        "{}:{}: field {} `{}` is not a finite number",
                        path.display(),
                        i + 1,
                        k + 1,
                        f[k]
                    )
                })
        };
        let id: u64 = f[0].parse().map_err(|_| {
            format!(
                "{}:{}: atom id `{}` is not an integer",
                path.display(),
                i + 1,
                f[0]
            )
        })?;
        let diameter = num(2)?;
        if diameter <= 0.0 {
            return Err(format!(
                "{}:{}: diameter {diameter} is outside the allowed range (0, inf)",
                path.display(),
                i + 1
            ));
        }
        let p = Vector3::new(num(4)?, num(5)?, num(6)?) * length_scale;
        atoms.push((id, p, diameter / 2.0 * length_scale));
        if atoms.len() == n {
            break;
        }
    }
    if atoms.len() != n {
        return Err(format!(
            "{}: the header declares {n} atoms but the Atoms section holds {}",
            path.display(),
            atoms.len()
        ));
    }
    atoms.sort_by_key(|a| a.0);
    Ok(atoms.into_iter().map(|(_, p, r)| (p, r)).collect())
}

/// A uniform hash grid for neighbour queries among spheres of radius ≤ `cell / 2`.
pub(crate) struct Grid {
    cell: f64,
    cells: HashMap<(i64, i64, i64), Vec<usize>>,
}

impl Grid {
    pub(crate) fn new(cell: f64) -> Self {
        Self {
            cell,
            cells: HashMap::new(),
        }
    }

    fn key(&self, p: &Vector3<f64>) -> (i64, i64, i64) {
        (
            (p.x / self.cell).floor() as i64,
            (p.y / self.cell).floor() as i64,
            (p.z / self.cell).floor() as i64,
        )
    }

    pub(crate) fn insert(&mut self, p: &Vector3<f64>, index: usize) {
        let k = self.key(p);
        self.cells.entry(k).or_default().push(index);
    }

    pub(crate) fn neighbours(&self, p: &Vector3<f64>) -> impl Iterator<Item = usize> + '_ {
        let (x, y, z) = self.key(p);
        (-1..=1)
            .flat_map(move |dx| (-1..=1).flat_map(move |dy| (-1..=1).map(move |dz| (dx, dy, dz))))
            .filter_map(move |(dx, dy, dz)| {
                // Saturating: a centre at an absurd coordinate must not overflow.
                self.cells.get(&(
                    x.saturating_add(dx),
                    y.saturating_add(dy),
                    z.saturating_add(dz),
                ))
            })
            .flatten()
            .copied()
    }
}

/// Pairs of spheres overlapping by more than `tolerance` × the smaller radius:
/// `(i, j, overlap_m)`, at most `limit` of them.
pub fn overlapping_pairs(
    spheres: &[(Vector3<f64>, f64)],
    tolerance: f64,
    limit: usize,
) -> Vec<(usize, usize, f64)> {
    let r_max = spheres.iter().map(|s| s.1).fold(0.0, f64::max);
    if r_max <= 0.0 {
        return Vec::new();
    }
    let mut grid = Grid::new(2.0 * r_max);
    let mut out = Vec::new();
    for (i, (p, r)) in spheres.iter().enumerate() {
        for j in grid.neighbours(p) {
            let (q, s) = spheres[j];
            let overlap = r + s - (p - q).norm();
            if overlap > tolerance * r.min(s) {
                out.push((j, i, overlap));
                if out.len() >= limit {
                    return out;
                }
            }
        }
        grid.insert(p, i);
    }
    out
}
