//! Checking a scene file before the run: structure (types, unknown keys) through serde with the
//! parser's spans, then every value against its allowed range, collecting all problems with
//! file, line and key. Material and law parameters are checked by the law crate itself
//! ([`mdr_contact::ContactError`]), so the allowed ranges are stated once.
//!
//! The file's structure, the checker and `[run]` are here; `[contact]`, `[[particles]]` and
//! `[[walls]]` have a module each.

use super::problems::{KeyPath, Locator, Problem, Problems, Severity};
use super::schema::*;
use super::{ContactSpec, NormalSpec, Scene, ROLLING_FRICTION_KEY};
use crate::laws::registry;
use crate::placement::{self, ParticleInit, RadiusLaw};
use crate::walls::{self, Wall, WallPiece};
use mdr_contact::damping::NoDamping;
use mdr_contact::normal::{AdhesiveMdr, MdrElastoPlastic};
use mdr_contact::params::{Declared, ParamProblem};
use mdr_contact::{ContactError, ContactPair, Material};
use nalgebra::Vector3;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::path::{Path, PathBuf};

mod adhesion;
mod contact_section;
mod particle_section;
mod wall_section;

/// Largest number of particles a scene may create.
pub const MAX_PARTICLES: u64 = 1_000_000;
/// Largest number of steps a run may take.
pub const MAX_STEPS: f64 = 1e10;
/// A force-mode step coarser than `t_c / MIN_STEPS_HARD` is refused (the contact would be
/// resolved so coarsely that symplectic Euler gains energy in every impact).
pub const MIN_STEPS_HARD: f64 = 5.0;
/// Default of `[run] max_energy_drift`: a run whose energy balance drifts by more than this
/// fraction of its energy scale stops. The built-in column, drum and funnel drift by less than
/// 0.5 % (docs/user-guide.md); a wall that pushes spheres the wrong way, or a time step far too
/// coarse, drifts by tens of per cent.
pub const DEFAULT_MAX_ENERGY_DRIFT: f64 = 0.05;
/// Initial overlaps above this fraction of the smaller radius are refused.
pub const OVERLAP_TOLERANCE: f64 = 0.01;

pub use adhesion::mixed_work_of_adhesion;

/// Read and check a scene file. Every problem is reported with its file, line and key; warnings
/// are returned inside the [`Scene`].
pub fn load_scene(path: &Path) -> Result<Scene, Problems> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        Problems(vec![Problem {
            severity: Severity::Error,
            file: path.to_path_buf(),
            line: 0,
            column: 0,
            key: String::new(),
            message: format!("cannot read the scene file: {e}"),
        }])
    })?;
    parse_scene(path, &text)
}

/// Check a scene given as text; `path` locates it (messages, relative file names).
pub fn parse_scene(path: &Path, text: &str) -> Result<Scene, Problems> {
    if text.trim().is_empty() {
        return Err(Problems(vec![Problem {
            severity: Severity::Error,
            file: path.to_path_buf(),
            line: 0,
            column: 0,
            key: String::new(),
            message: format!(
                "the scene file is empty ({} bytes): a scene needs [run], [[material]], [contact] \
                 and [[particles]] (copy one of scenes/*.toml)",
                text.len()
            ),
        }]));
    }
    let loc = Locator::new(path, text);
    let (file, structural) = parse_structure(&loc, text);
    let Some(file) = file else {
        return Err(Problems(structural));
    };
    let mut checker = Checker {
        loc: &loc,
        problems: structural,
        base: path.parent().map(Path::to_path_buf).unwrap_or_default(),
    };
    let scene = checker.scene(path, file);
    let mut problems = checker.problems;
    problems.sort_by_key(|p| (std::cmp::Reverse(p.severity), p.line, p.column));
    match scene {
        Some(mut scene) if !problems.iter().any(|p| p.severity == Severity::Error) => {
            scene.warnings = problems;
            Ok(scene)
        }
        _ => Err(Problems(problems)),
    }
}

/// serde pass. An unknown key alone on its line is blanked out (same length, so spans stay
/// valid) and parsing resumes, so every unknown key is reported at once, and the values are
/// still checked. Returns the parsed file (if any) and the structural problems.
fn parse_structure(loc: &Locator<'_>, text: &str) -> (Option<SceneFile>, Vec<Problem>) {
    let mut work = text.to_owned();
    let mut problems = Vec::new();
    for _ in 0..64 {
        match toml::from_str::<SceneFile>(&work) {
            Ok(file) => return (Some(file), problems),
            Err(e) => {
                let span = e.span();
                let message = with_suggestion(e.message().trim());
                let (line_range, mut key) = span
                    .as_ref()
                    .map(|s| line_of(&work, s.start))
                    .map_or((None, String::new()), |(r, k)| (Some(r), k));
                let mut message = message;
                if message.starts_with("duplicate key") {
                    let line = line_range.clone().map_or("", |r| work[r].trim());
                    if let Some(table) = line.strip_prefix('[') {
                        key = table.trim_matches(['[', ']', ' ']).to_owned();
                        message = format!(
                            "duplicate table: [{key}] is defined a second time here (a table \
                             written once per file; [[…]] for a list of tables)"
                        );
                    } else {
                        message = format!(
                            "duplicate key: `{key}` is given a second time in the same table; keep one"
                        );
                    }
                }
                problems.push(loc.at_span(Severity::Error, span.clone(), key, message.clone()));
                let Some(range) = line_range else { break };
                let line = &work[range.clone()];
                let resumable = message.starts_with("unknown field")
                    && line.contains('=')
                    && !line.contains('{')
                    && !line.trim_start().starts_with('[')
                    && line.matches('[').count() == line.matches(']').count()
                    && !line.contains("\"\"\"");
                if !resumable {
                    break;
                }
                work.replace_range(range.clone(), &" ".repeat(range.len()));
            }
        }
    }
    problems.sort_by_key(|p| (p.line, p.column));
    (None, problems)
}

/// A serde message about an unknown key or variant (`` unknown field `x`, expected one of `a`,
/// `b` ``), with the nearest allowed name added (`did you mean`) where one is close: within a
/// third of the name's length in edits (Levenshtein), at least one.
fn with_suggestion(message: &str) -> String {
    let unknown = ["unknown field `", "unknown variant `"]
        .iter()
        .find_map(|p| message.strip_prefix(p))
        .and_then(|rest| rest.split_once('`'));
    let Some((name, rest)) = unknown else {
        return message.to_owned();
    };
    let allowed = rest.split('`').skip(1).step_by(2);
    let best = allowed
        .map(|a| (strsim::levenshtein(name, a), a))
        .min_by_key(|(d, _)| *d);
    match best {
        Some((d, a)) if d > 0 && d <= (name.chars().count() / 3).max(1) => {
            format!("{message}; did you mean `{a}`?")
        }
        _ => message.to_owned(),
    }
}

/// The byte range of the line holding `offset` and the key written on it (text before `=`).
fn line_of(text: &str, offset: usize) -> (std::ops::Range<usize>, String) {
    let offset = offset.min(text.len());
    let start = text[..offset].rfind('\n').map_or(0, |i| i + 1);
    let end = text[offset..].find('\n').map_or(text.len(), |i| offset + i);
    let line = &text[start..end];
    let key = line
        .split_once('=')
        .map(|(k, _)| k.trim().trim_matches('"').to_owned())
        .unwrap_or_default();
    (start..end, key)
}

struct Checker<'a, 'b> {
    loc: &'a Locator<'b>,
    problems: Vec<Problem>,
    base: PathBuf,
}

/// Map the law crate's parameter names to the scene file's keys.
fn key_for(name: &str) -> &str {
    match name {
        "youngs_modulus" => "youngs_pa",
        "poisson_ratio" => "poisson_ratio",
        "density" => "density_kg_per_m3",
        "mu" => "friction",
        "gamma_n" => "damping_gamma_n_per_m_s",
        "eta" => "damping_eta",
        "tangential_damping_ratio" => "damping_tangential_ratio",
        "mu_r" => "rolling_friction",
        other => other,
    }
}

impl Checker<'_, '_> {
    fn error(&mut self, path: &KeyPath, message: impl Into<String>) {
        let p = self.loc.problem(Severity::Error, path, message);
        self.problems.push(p);
    }

    fn warn(&mut self, path: &KeyPath, message: impl Into<String>) {
        let p = self.loc.problem(Severity::Warning, path, message);
        self.problems.push(p);
    }

    /// A law-crate error on the table at `table`.
    fn contact_error(&mut self, table: &KeyPath, e: ContactError) {
        let name = match &e {
            ContactError::NotFinite { name, .. }
            | ContactError::OutOfRange { name, .. }
            | ContactError::TooFew { name, .. }
            | ContactError::InvalidTable { name, .. } => *name,
        };
        self.error(&table.key(key_for(name)), e.to_string());
    }

    fn finite(&mut self, path: &KeyPath, v: f64) -> Option<f64> {
        if v.is_finite() {
            Some(v)
        } else {
            self.error(path, format!("must be a finite number, got {v}"));
            None
        }
    }

    /// `[run] periodic_x_m` and `periodic_y_m`: both or neither, each `[lo, hi]` with
    /// `lo < hi` finite, on the neighbour-list path only, and without `delete_below_m` (parked
    /// spheres would sit outside the box).
    fn periodic_box(&mut self, r: &RunSection, run: &KeyPath) -> Option<[(f64, f64); 2]> {
        let (x, y) = match (r.periodic_x_m, r.periodic_y_m) {
            (None, None) => return None,
            (Some(x), Some(y)) => (x, y),
            (Some(_), None) => {
                self.error(
                    &run.key("periodic_x_m"),
                    "needs periodic_y_m too: the box is periodic in x and y together",
                );
                return None;
            }
            (None, Some(_)) => {
                self.error(
                    &run.key("periodic_y_m"),
                    "needs periodic_x_m too: the box is periodic in x and y together",
                );
                return None;
            }
        };
        let mut ok = true;
        for (name, [lo, hi]) in [("periodic_x_m", x), ("periodic_y_m", y)] {
            if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                self.error(
                    &run.key(name),
                    format!("= [{lo}, {hi}] m: needs finite lo < hi (the box's range, m)"),
                );
                ok = false;
            }
        }
        let key = run.key("periodic_x_m");
        if r.coupling == CouplingMode::Restitution || r.force_path == Some(ForcePath::Rapier) {
            self.error(
                &key,
                "applies to the neighbour-list path only (coupling = \"force\", force_path = \"neighbour_list\")",
            );
            ok = false;
        }
        if r.delete_below_m.is_some() {
            self.error(
                &key,
                "cannot be combined with delete_below_m (removed spheres are parked outside the box)",
            );
            ok = false;
        }
        ok.then_some([(x[0], x[1]), (y[0], y[1])])
    }

    fn positive(&mut self, path: &KeyPath, v: f64) -> Option<f64> {
        let v = self.finite(path, v)?;
        if v > 0.0 {
            Some(v)
        } else {
            self.error(path, format!("= {v} is outside the allowed range (0, inf)"));
            None
        }
    }

    fn non_negative(&mut self, path: &KeyPath, v: f64) -> Option<f64> {
        let v = self.finite(path, v)?;
        if v >= 0.0 {
            Some(v)
        } else {
            self.error(path, format!("= {v} is outside the allowed range [0, inf)"));
            None
        }
    }

    fn vector(&mut self, path: &KeyPath, v: [f64; 3]) -> Option<Vector3<f64>> {
        if v.iter().all(|c| c.is_finite()) {
            Some(Vector3::from(v))
        } else {
            self.error(
                path,
                format!("every component must be a finite number, got {v:?}"),
            );
            None
        }
    }

    fn unit(&mut self, path: &KeyPath, v: [f64; 3]) -> Option<Vector3<f64>> {
        let v = self.vector(path, v)?;
        let n = v.norm();
        if n > 0.0 {
            Some(v / n)
        } else {
            self.error(path, "must be a non-zero vector");
            None
        }
    }

    fn require<T: Copy>(
        &mut self,
        table: &KeyPath,
        key: &str,
        v: Option<T>,
        why: &str,
    ) -> Option<T> {
        if v.is_none() {
            self.error(table, format!("missing key `{key}` ({why})"));
        }
        v
    }

    fn unused(&mut self, table: &KeyPath, keys: &[(&str, bool)], why: &str) {
        for (key, given) in keys {
            if *given {
                self.error(
                    &table.key(key),
                    format!("this key is not used {why}: remove it"),
                );
            }
        }
    }

    fn read_file(&mut self, path: &KeyPath, name: &str) -> PathBuf {
        let p = PathBuf::from(name);
        let p = if p.is_absolute() {
            p
        } else {
            self.base.join(p)
        };
        if !p.exists() {
            self.error(path, format!("file `{}` not found", p.display()));
        }
        p
    }

    fn scene(&mut self, path: &Path, file: SceneFile) -> Option<Scene> {
        let root = KeyPath::root();
        let run = root.key("run");
        let r = &file.run;
        if r.name.trim().is_empty()
            || r.name.contains(['/', '\\'])
            || r.name.chars().any(char::is_control)
        {
            self.error(
                &run.key("name"),
                "must be a non-empty file-name-safe string (no `/`)",
            );
        }
        let duration = self.positive(&run.key("duration_s"), r.duration_s);
        if duration.is_some_and(|d| d > 1e9) {
            self.error(
                &run.key("duration_s"),
                "is outside the allowed range (0, 1e9] s",
            );
        }
        let output = self.positive(&run.key("output_interval_s"), r.output_interval_s);
        if let (Some(o), Some(d)) = (output, duration) {
            if o > d {
                self.warn(
                    &run.key("output_interval_s"),
                    format!("= {o} s is longer than the run ({d} s): only the first and last frames are written"),
                );
            }
        }
        let checkpoint = r
            .checkpoint_interval_s
            .and_then(|c| self.positive(&run.key("checkpoint_interval_s"), c));
        let energy = match r.energy_interval_s {
            Some(e) => self.positive(&run.key("energy_interval_s"), e),
            None => output.map(|o| o / 10.0),
        };
        let max_energy_drift = match (r.coupling, r.max_energy_drift) {
            (CouplingMode::Restitution, Some(_)) => {
                self.warn(
                    &run.key("max_energy_drift"),
                    "is ignored in restitution mode: its books do not itemise what the impulses dissipate",
                );
                None
            }
            (CouplingMode::Restitution, None) => None,
            (CouplingMode::Force, Some(f)) => self.positive(&run.key("max_energy_drift"), f),
            (CouplingMode::Force, None) => Some(DEFAULT_MAX_ENERGY_DRIFT),
        };
        let max_speed_given = r
            .max_speed_m_per_s
            .and_then(|v| self.positive(&run.key("max_speed_m_per_s"), v));
        let steps_per_contact = match r.steps_per_contact {
            Some(s) => {
                let s = self.positive(&run.key("steps_per_contact"), s);
                if s.is_some_and(|s| s < MIN_STEPS_HARD) {
                    self.error(
                        &run.key("steps_per_contact"),
                        format!("is outside the allowed range [{MIN_STEPS_HARD}, inf)"),
                    );
                }
                s
            }
            None => Some(mdr_rapier::timestep::MIN_STEPS_PER_CONTACT),
        };
        if r.coupling == CouplingMode::Restitution {
            let c = &file.contact;
            if c.normal != MdrElastoPlastic::DECLARATION.name
                && c.normal != AdhesiveMdr::DECLARATION.name
            {
                self.error(
                    &root.key("contact").key("normal"),
                    "restitution coupling needs normal = \"mdr\" or \"adhesive_mdr\" (its restitution comes from the MDR energy route)",
                );
            }
            let damped = c
                .damping
                .as_deref()
                .is_some_and(|d| d != NoDamping::DECLARATION.name);
            if damped || c.number(ROLLING_FRICTION_KEY).is_some_and(|m| m > 0.0) {
                self.warn(
                    &root.key("contact"),
                    "restitution coupling ignores damping and rolling resistance (only e_n(v) and μ enter the impulses)",
                );
            }
        }
        if let Some(skin) = r.neighbour_skin_m {
            let key = run.key("neighbour_skin_m");
            if r.coupling == CouplingMode::Restitution || r.force_path == Some(ForcePath::Rapier) {
                self.error(
                    &key,
                    "applies to the neighbour-list path only (coupling = \"force\", force_path = \"neighbour_list\")",
                );
            } else if !(skin.is_finite() && skin > 0.0) {
                self.error(
                    &key,
                    format!("= {skin} m is outside the allowed range (0, inf) m"),
                );
            }
        }
        if r.coupling == CouplingMode::Restitution && r.force_path.is_some() {
            self.error(
                &run.key("force_path"),
                "applies to coupling = \"force\" only (restitution mode runs on rapier's pipeline)",
            );
        }
        if r.discharge_height_m.is_some()
            && !matches!(r.headline, Headline::Hopper | Headline::Funnel)
        {
            self.error(
                &run.key("discharge_height_m"),
                "is used only with headline = \"hopper\" or \"funnel\"",
            );
        }
        if let Some(h) = r.delete_below_m {
            if let Some(h) = self.finite(&run.key("delete_below_m"), h) {
                if let Some(d) = r.discharge_height_m.filter(|d| d.is_finite() && *d < h) {
                    self.error(
                        &run.key("discharge_height_m"),
                        format!("= {d} m is below delete_below_m = {h} m: a sphere is removed before it counts as discharged"),
                    );
                }
            }
        }
        if let Some(sweep) = &r.orifice_sweep_m {
            let key = run.key("orifice_sweep_m");
            if r.headline != Headline::Hopper {
                self.error(&key, "is used only with headline = \"hopper\"");
            } else if sweep.len() < 3 {
                self.error(
                    &key,
                    format!(
                        "has {} diameter(s): at least 3 are needed to fit Beverloo's C and k",
                        sweep.len()
                    ),
                );
            } else if sweep.iter().any(|d| !(d.is_finite() && *d > 0.0)) {
                self.error(
                    &key,
                    format!("= {sweep:?}: every diameter must be in (0, inf) m"),
                );
            } else if sweep.windows(2).any(|w| w[1] <= w[0]) {
                self.error(&key, format!("= {sweep:?}: the diameters must increase"));
            } else if file
                .walls
                .iter()
                .filter(|w| w.kind == WallKind::OrificePlate)
                .count()
                != 1
            {
                self.error(
                    &key,
                    "needs exactly one wall of kind orifice_plate (its diameter is swept)",
                );
            }
        }
        let discharge = r
            .discharge_height_m
            .and_then(|h| self.finite(&run.key("discharge_height_m"), h));
        let periodic = self.periodic_box(r, &run);

        let gravity = match &file.gravity {
            Some(g) => self.vector(
                &root.key("gravity").key("acceleration_m_per_s2"),
                g.acceleration_m_per_s2,
            ),
            None => Some(Vector3::zeros()),
        };

        // Materials (ranges checked by the law crate).
        let mut materials: Vec<(String, Material)> = Vec::new();
        let mut materials_ok = true;
        for (i, m) in file.material.iter().enumerate() {
            let table = root.key("material").index(i);
            if materials.iter().any(|(n, _)| n == &m.name) {
                self.error(
                    &table.key("name"),
                    format!("material `{}` is defined twice", m.name),
                );
            }
            match Material::new(m.youngs_pa, m.poisson_ratio, m.density_kg_per_m3) {
                Ok(mat) => materials.push((m.name.clone(), mat)),
                Err(e) => {
                    materials_ok = false;
                    self.contact_error(&table, e);
                }
            }
        }
        if file.material.is_empty() {
            self.error(
                &root,
                "missing `[[material]]`: at least one material is required",
            );
        }
        let material_index = |checker: &mut Self, path: &KeyPath, name: &str| -> Option<usize> {
            let i = materials.iter().position(|(n, _)| n == name);
            if i.is_none() && materials_ok {
                let known: Vec<&str> = materials.iter().map(|(n, _)| n.as_str()).collect();
                checker.error(
                    path,
                    format!("unknown material `{name}` (defined: {})", known.join(", ")),
                );
            }
            i
        };

        let mut contact = self.contact(&file.contact);
        let gammas = self.works_of_adhesion(&file);

        // Particles.
        let mut rng = ChaCha8Rng::seed_from_u64(r.seed);
        let mut particles: Vec<ParticleInit> = Vec::new();
        let mut total: u64 = 0;
        for (g, group) in file.particles.iter().enumerate() {
            let table = root.key("particles").index(g);
            let material = material_index(self, &table.key("material"), &group.material);
            let velocity = match group.velocity_m_per_s {
                Some(v) => self.vector(&table.key("velocity_m_per_s"), v),
                None => Some(Vector3::zeros()),
            };
            let placed = self.place_group(&table, group, &mut rng, &mut total);
            let placed = self.trim_to_cylinder(&table, group, placed);
            let classes = self.radius_classes(&table, group);
            if let (Some(material), Some(velocity), Some(placed), Some(classes)) =
                (material, velocity, placed, classes)
            {
                particles.extend(placed.into_iter().map(|(p, r, v)| ParticleInit {
                    position: p,
                    radius: classes.map_or(r, |(lo, step)| {
                        // Down to the class below: never larger than drawn, so never overlapping.
                        lo + ((r - lo) / step + 1e-9).floor().max(0.0) * step
                    }),
                    velocity: v.unwrap_or(velocity),
                    material,
                    group: g,
                }));
            }
        }
        if file.particles.is_empty() {
            self.error(&root, "missing `[[particles]]`: the scene has no particles");
        }

        // Walls.
        let mut walls_out = Vec::new();
        for (w, wall) in file.walls.iter().enumerate() {
            let table = root.key("walls").index(w);
            let material = material_index(self, &table.key("material"), &wall.material);
            let neighbour_list = !(file.run.coupling == CouplingMode::Restitution
                || file.run.force_path == Some(ForcePath::Rapier));
            if wall.exact_surface == Some(true) && !neighbour_list {
                self.error(
                    &table.key("exact_surface"),
                    "applies to the neighbour-list path only (coupling = \"force\", force_path = \"neighbour_list\"): remove it or set it to false",
                );
            }
            if let (Some(wall_out), Some(material)) = (self.wall(&table, wall, w), material) {
                walls_out.push(Wall {
                    material,
                    ..wall_out
                });
            }
        }

        if let Some(contact) = &mut contact {
            self.adhesion(&gammas, &particles, &walls_out, contact);
        }

        // Placement against placement and walls, within each group's allowance.
        let allowance: Vec<f64> = file
            .particles
            .iter()
            .enumerate()
            .map(|(g, group)| match group.max_initial_overlap_fraction {
                Some(f) if (0.0..=0.5).contains(&f) => f,
                Some(f) => {
                    self.error(
                        &root
                            .key("particles")
                            .index(g)
                            .key("max_initial_overlap_fraction"),
                        format!("= {f} is outside the allowed range [0, 0.5]"),
                    );
                    OVERLAP_TOLERANCE
                }
                None => OVERLAP_TOLERANCE,
            })
            .collect();
        if !particles.is_empty() && self.problems.iter().all(|p| p.severity != Severity::Error) {
            self.check_overlaps(&root, &particles, &walls_out, &allowance);
        }

        // Time step.
        let (Some(duration), Some(output), Some(energy), Some(gravity), Some(contact), Some(spc)) = (
            duration,
            output,
            energy,
            gravity,
            contact,
            steps_per_contact,
        ) else {
            return None;
        };
        if particles.is_empty() || self.problems.iter().any(|p| p.severity == Severity::Error) {
            return None;
        }
        let max_speed = max_speed_given.unwrap_or_else(|| estimate_max_speed(&particles, &gravity));
        let shortest = shortest_contact_pair(&particles, &walls_out, &materials)?;
        let contact_time = shortest.hertz_contact_time(max_speed);
        let (dt, dt_auto) = match r.dt_s {
            TimeStep::Auto(_) => {
                if max_speed_given.is_none() {
                    self.warn(
                        &run.key("dt_s"),
                        format!(
                            "dt_s = \"auto\" without `max_speed_m_per_s`: assuming {max_speed:.3} m/s \
                             (initial speeds + free fall over the scene's height)"
                        ),
                    );
                }
                // The plugin's helper: Hertz contact time of the shortest pair / steps.
                match mdr_rapier::stable_time_step(&shortest, max_speed, spc) {
                    Ok(advice) => (advice.time_step, true),
                    Err(e) => {
                        self.error(&run.key("dt_s"), e.to_string());
                        return None;
                    }
                }
            }
            TimeStep::Seconds(dt) => {
                let dt = self.positive(&run.key("dt_s"), dt)?;
                (dt, false)
            }
        };
        if r.coupling == CouplingMode::Force {
            let steps = if dt_auto { spc } else { contact_time / dt }; // t_c / dt may round below spc
            if steps < MIN_STEPS_HARD {
                self.error(
                    &run.key("dt_s"),
                    format!(
                        "= {dt:.3e} s is far too large: the shortest contact (Hertz time {contact_time:.3e} s \
                         at {max_speed:.3} m/s) would take {steps:.2} steps; allowed (0, {:.3e}] s, \
                         recommended {:.3e} s or dt_s = \"auto\"",
                        contact_time / MIN_STEPS_HARD,
                        contact_time / mdr_rapier::timestep::MIN_STEPS_PER_CONTACT
                    ),
                );
                return None;
            }
            if steps < mdr_rapier::timestep::MIN_STEPS_PER_CONTACT {
                self.warn(
                    &run.key("dt_s"),
                    format!(
                        "time step {dt:.3e} s resolves a {contact_time:.3e} s contact with {steps:.1} steps \
                         (fewer than {}): restitution and energy books lose accuracy",
                        mdr_rapier::timestep::MIN_STEPS_PER_CONTACT
                    ),
                );
            }
        }
        let steps = duration / dt;
        if steps > MAX_STEPS {
            self.error(
                &run.key("duration_s"),
                format!("the run would take {steps:.3e} steps (allowed at most {MAX_STEPS:.0e}): shorten it or enlarge dt_s"),
            );
            return None;
        }
        let work = steps * particles.len() as f64;
        if work > 1e12 {
            self.warn(
                &run.key("duration_s"),
                format!("the run is {work:.2e} particle-steps: hours to days of computing"),
            );
        }
        if energy < dt {
            self.warn(
                &run.key("energy_interval_s"),
                "is shorter than the time step: one row per step",
            );
        }
        self.jamming_hint(&file, &particles);
        Some(Scene {
            file: path.to_path_buf(),
            source: file.clone(),
            name: r.name.clone(),
            seed: r.seed,
            duration,
            dt,
            dt_auto,
            max_speed,
            contact_time,
            output_interval: output,
            checkpoint_interval: checkpoint,
            energy_interval: energy,
            max_energy_drift,
            coupling: r.coupling,
            force_path: r.force_path.unwrap_or_default(),
            headline: r.headline,
            contact_network: r.contact_network,
            discharge_height: discharge,
            periodic,
            gravity,
            materials,
            contact,
            particles,
            walls: walls_out,
            warnings: Vec::new(),
        })
    }
}

/// Orifices narrower than this many mean particle diameters jam: arches form over them and
/// stop the flow for good (in 3D silos the mean avalanche between jams grows without bound
/// only as `D/d` approaches about 5; Zuriguel, Garcimartín, Maza, Pugnaloni & Pastor, Phys.
/// Rev. E 71, 051303, 2005). The scene check warns below it, and the hopper headline reports
/// "jammed" instead of a flow rate.
pub const JAMMING_RATIO: f64 = 4.0;

impl Checker<'_, '_> {
    /// Orifices (an orifice plate's `orifice_diameter_m`, each of `orifice_sweep_m`) narrower
    /// than [`JAMMING_RATIO`] mean particle diameters jam.
    fn jamming_hint(&mut self, file: &SceneFile, particles: &[ParticleInit]) {
        if particles.is_empty() {
            return;
        }
        let d = 2.0 * particles.iter().map(|p| p.radius).sum::<f64>() / particles.len() as f64;
        let limit = JAMMING_RATIO;
        let root = KeyPath::root();
        let mut orifices: Vec<(KeyPath, f64)> = file
            .walls
            .iter()
            .enumerate()
            .filter(|(_, w)| w.kind == WallKind::OrificePlate)
            .filter_map(|(i, w)| {
                let key = root.key("walls").index(i).key("orifice_diameter_m");
                w.orifice_diameter_m.map(|o| (key, o))
            })
            .collect();
        if let Some(sweep) = &file.run.orifice_sweep_m {
            let key = root.key("run").key("orifice_sweep_m");
            orifices = sweep.iter().map(|&o| (key.clone(), o)).collect();
        }
        for (key, o) in orifices {
            if o < limit * d {
                self.warn(
                    &key,
                    format!(
                        "an orifice of {o} m is {:.2} mean particle diameters (d = {d:.4e} m): below \
                         about {limit} d arches jam it and the flow stops (the hopper headline \
                         reports \"jammed\"); Beverloo's law holds from about 6 d",
                        o / d
                    ),
                );
            }
        }
    }
}

/// Initial speeds plus the free-fall speed over the particles' vertical extent (along gravity),
/// at least 0.1 m/s.
fn estimate_max_speed(particles: &[ParticleInit], gravity: &Vector3<f64>) -> f64 {
    let v0 = particles
        .iter()
        .map(|p| p.velocity.norm())
        .fold(0.0, f64::max);
    let g = gravity.norm();
    let fall = if g > 0.0 {
        let dir = gravity / g;
        let (lo, hi) = particles
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                let h = p.position.dot(&dir);
                (lo.min(h), hi.max(h))
            });
        (2.0 * g * (hi - lo).max(0.0)).sqrt()
    } else {
        0.0
    };
    (2.0 * v0 + fall).max(0.1)
}

/// The pair with the shortest Hertz contact time (the time scales as `(m²/(R E*²))^{1/5}` at any
/// speed): the smallest sphere of each material against every material, sphere or wall.
fn shortest_contact_pair(
    particles: &[ParticleInit],
    walls: &[Wall],
    materials: &[(String, Material)],
) -> Option<ContactPair> {
    let mut smallest: Vec<Option<f64>> = vec![None; materials.len()];
    for p in particles {
        let s = &mut smallest[p.material];
        *s = Some(s.map_or(p.radius, |r: f64| r.min(p.radius)));
    }
    let mut best: Option<(f64, ContactPair)> = None;
    let mut consider = |pair: Result<ContactPair, ContactError>| {
        if let Ok(pair) = pair {
            let t = pair.hertz_contact_time(1.0);
            if best.is_none_or(|(b, _)| t < b) {
                best = Some((t, pair));
            }
        }
    };
    for (i, ri) in smallest.iter().enumerate() {
        let Some(ri) = ri else { continue };
        for (j, rj) in smallest.iter().enumerate() {
            let Some(rj) = rj else { continue };
            consider(ContactPair::sphere_on_sphere(
                *ri,
                &materials[i].1,
                *rj,
                &materials[j].1,
            ));
        }
        for w in walls {
            consider(ContactPair::sphere_on_half_space(
                *ri,
                &materials[i].1,
                &materials[w.material].1,
            ));
        }
    }
    best.map(|(_, pair)| pair)
}
