//! `bench_bed`: throughput of the fast force-mode path of `mdr-rapier` on a settled bed, as
//! `mdr-dem bench bed` (the LAMMPS `gran/hertz/history` reference system of
//! `mdr_rapier::fast::bed::reference_system`; docs/performance.md). The CLI's timing loop lives in
//! the program, not in a library, so its few lines are repeated here with the same JSON keys.

use crate::errors::invalid;
use mdr_contact::damping::HertzianViscous;
use mdr_contact::model::WorkBooks;
use mdr_contact::normal::{Hertz, MdrElastoPlastic, NormalLaw, NormalModel};
use mdr_contact::rolling::NoRolling;
use mdr_contact::tangential::Mindlin;
use mdr_rapier::fast::bed::{reference_system, settled_bed, Bed, BedSpec};
use mdr_rapier::fast::rayon;
use mdr_rapier::fast::FastForceStepper;
use mdr_rapier::rapier::prelude::PhysicsWorld;
use pyo3::exceptions::{PyOSError, PyRuntimeError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Settings of one bench run.
#[derive(Debug, Clone, Copy)]
struct Settings {
    steps: usize,
    warmup: usize,
    skin: f64,
    orientation: bool,
    work_books: bool,
}

/// Figures of one run (the keys of `mdr-dem bench bed --json` that do not need OS clocks).
struct Figures {
    law: &'static str,
    particles: usize,
    wall_seconds: f64,
    contacts_per_particle: f64,
    floor_contacts: usize,
    rebuilds: u64,
    plastic_contact_fraction: f64,
    state_checksum: String,
}

/// FNV-1a (64 bit) over the bit patterns of `values`, as `bench bed`'s `state_checksum`.
fn fnv1a(values: impl Iterator<Item = f64>) -> u64 {
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for v in values {
        for byte in v.to_bits().to_le_bytes() {
            hash ^= u64::from(byte);
            hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    hash
}

fn timed<N: NormalModel>(
    normal: N,
    law: &'static str,
    bed: &Bed,
    s: Settings,
) -> Result<Figures, String>
where
    N::Law: Clone,
{
    let (stepper, world) = reference_system(normal, bed).map_err(|e| e.to_string())?;
    let stepper = stepper
        .skin(s.skin)
        .map_err(|e| e.to_string())?
        .track_orientation(s.orientation);
    if s.work_books {
        measure(stepper, world, law, bed, s)
    } else {
        measure(stepper.without_work_books(), world, law, bed, s)
    }
}

fn measure<N, B>(
    mut stepper: FastForceStepper<N, Mindlin, HertzianViscous, NoRolling, B>,
    mut world: PhysicsWorld,
    law: &'static str,
    bed: &Bed,
    s: Settings,
) -> Result<Figures, String>
where
    N: NormalModel,
    N::Law: Clone,
    B: WorkBooks,
{
    for _ in 0..s.warmup {
        stepper.step(&mut world).map_err(|e| e.to_string())?;
    }
    let rebuilds0 = stepper.rebuilds();
    let start = Instant::now();
    for _ in 0..s.steps {
        stepper.step(&mut world).map_err(|e| e.to_string())?;
    }
    let wall_seconds = start.elapsed().as_secs_f64();
    let report = stepper.last_report();
    let pairs = stepper.pairs();
    let (mut touching, mut plastic) = (0usize, 0usize);
    for q in 0..pairs.len() {
        if pairs.active[q] {
            touching += 1;
            let pair_law = stepper.sphere_law(pairs.i[q] as usize, pairs.j[q] as usize);
            let state = &pairs.history[q].contact.normal;
            if pair_law.normal.max_overlap(state) > pair_law.normal.yield_overlap() {
                plastic += 1;
            }
        }
    }
    let p = stepper.particles();
    let vectors = p.position.iter().chain(&p.linvel).chain(&p.angvel);
    Ok(Figures {
        law,
        particles: bed.len(),
        wall_seconds,
        contacts_per_particle: 2.0 * report.sphere_contacts as f64 / bed.len() as f64,
        floor_contacts: report.surface_contacts,
        rebuilds: stepper.rebuilds() - rebuilds0,
        plastic_contact_fraction: if touching > 0 {
            plastic as f64 / touching as f64
        } else {
            0.0
        },
        state_checksum: format!("{:016x}", fnv1a(vectors.flat_map(|v| [v.x, v.y, v.z]))),
    })
}

/// The repository's reference bed `benches/lammps/settled.data`, looked for in the repository
/// this package was built from, then in the working directory and its parents.
fn default_data() -> PyResult<PathBuf> {
    let rel = Path::new("benches/lammps/settled.data");
    let mut candidates: Vec<PathBuf> = Path::new(env!("CARGO_MANIFEST_DIR"))
        .ancestors()
        .map(|a| a.join(rel))
        .collect();
    if let Ok(cwd) = std::env::current_dir() {
        candidates.extend(cwd.ancestors().map(|a| a.join(rel)));
    }
    candidates
        .iter()
        .find(|c| c.is_file())
        .cloned()
        .ok_or_else(|| {
            invalid(
                "data",
                "the reference bed `benches/lammps/settled.data` was not found in the repository \
             or above the working directory; pass data=PATH or count=N",
            )
        })
}

/// Throughput of the fast force-mode path on a settled bed (as `mdr-dem bench bed`): the LAMMPS
/// data file `data` (default: the repository's 10,000-sphere reference bed), or, with `count`, a bed of
/// `count` spheres poured and settled with `settle_steps` steps first (untimed). `law`: "hertz"
/// or "mdr" (`q_c = qc` in reduced units, Θ = 0.37 E*); `steps` timed steps after `warmup`;
/// `threads` worker threads; `tile`: repeat the bed tile × tile times. Returns a dict:
/// particle_steps_per_s, ms_per_step, wall_seconds, contacts_per_particle, floor_contacts,
/// rebuilds, plastic_contact_fraction, state_checksum, law, particles, steps, threads,
/// orientation, work_books. The GIL is released during the run.
#[pyfunction]
#[pyo3(signature = (data = None, *, law = "hertz", steps = 10_000, warmup = 2_000, threads = 1,
    tile = 1, qc = 10.0, skin = 0.1, no_orientation = false, no_work_books = false, count = None,
    settle_steps = 40_000, seed = 1))]
#[allow(clippy::too_many_arguments)]
pub fn bench_bed<'py>(
    py: Python<'py>,
    data: Option<PathBuf>,
    law: &str,
    steps: usize,
    warmup: usize,
    threads: usize,
    tile: usize,
    qc: f64,
    skin: f64,
    no_orientation: bool,
    no_work_books: bool,
    count: Option<usize>,
    settle_steps: usize,
    seed: u64,
) -> PyResult<Bound<'py, PyDict>> {
    for (name, value) in [("steps", steps), ("threads", threads), ("tile", tile)] {
        if value == 0 {
            return Err(invalid(name, "0 is outside the allowed range [1, inf)"));
        }
    }
    if count == Some(0) {
        return Err(invalid("count", "0 is outside the allowed range [1, inf)"));
    }
    if !(skin.is_finite() && skin > 0.0) {
        return Err(invalid("skin", format!("{skin} (must be finite and > 0)")));
    }
    let mdr = match law {
        "hertz" => None,
        "mdr" => Some(MdrElastoPlastic::new(qc, 0.37).map_err(crate::errors::contact(false))?),
        other => {
            return Err(invalid(
                "law",
                format!("`{other}` (allowed: \"hertz\", \"mdr\")"),
            ))
        }
    };
    let settings = Settings {
        steps,
        warmup,
        skin,
        orientation: !no_orientation,
        work_books: !no_work_books,
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    let bed = match count {
        Some(count) => {
            let spec = BedSpec {
                count,
                settle_steps,
                seed,
                ..BedSpec::default()
            };
            py.detach(|| pool.install(|| settled_bed(&spec)))
                .map_err(|e| PyRuntimeError::new_err(e.to_string()))?
        }
        None => {
            let path = match data {
                Some(p) => p,
                None => default_data()?,
            };
            Bed::read_lammps(&path)
                .map_err(|e| PyOSError::new_err(format!("reading {}: {e}", path.display())))?
        }
    };
    if (0..bed.len())
        .any(|i| (bed.diameter[i] - 1.0).abs() > 1e-12 || (bed.density[i] - 1.0).abs() > 1e-12)
    {
        return Err(invalid(
            "data",
            "bench_bed expects the reference bed (every sphere of diameter 1 and density 1)",
        ));
    }
    let bed = if tile > 1 { bed.tiled(tile, tile) } else { bed };
    let figures = py
        .detach(|| {
            pool.install(|| match mdr {
                None => timed(Hertz, "hertz", &bed, settings),
                Some(model) => timed(model, "mdr", &bed, settings),
            })
        })
        .map_err(PyRuntimeError::new_err)?;
    let dict = PyDict::new(py);
    let particle_steps = (figures.particles * steps) as f64;
    dict.set_item(
        "particle_steps_per_s",
        particle_steps / figures.wall_seconds,
    )?;
    dict.set_item("ms_per_step", 1e3 * figures.wall_seconds / steps as f64)?;
    dict.set_item("wall_seconds", figures.wall_seconds)?;
    dict.set_item("contacts_per_particle", figures.contacts_per_particle)?;
    dict.set_item("floor_contacts", figures.floor_contacts)?;
    dict.set_item("rebuilds", figures.rebuilds)?;
    dict.set_item("plastic_contact_fraction", figures.plastic_contact_fraction)?;
    dict.set_item("state_checksum", figures.state_checksum)?;
    dict.set_item("law", figures.law)?;
    dict.set_item("particles", figures.particles)?;
    dict.set_item("steps", steps)?;
    dict.set_item("threads", threads)?;
    dict.set_item("orientation", settings.orientation)?;
    dict.set_item("work_books", settings.work_books)?;
    Ok(dict)
}
