//! The energy books: where the energy of a run is at one time, and the CSV time series.
//!
//! With no external work the sum `kinetic + rotational + gravitational + elastic (normal,
//! tangential, rolling) + plastic + friction + damping + rolling + stiffness (tangential,
//! rolling)` is constant up to the time-integration error; a kinematic wall's work on the
//! particles is booked in `wall_work_j` and subtracted, so `balance_j` stays constant then too.
//! The two stiffness books hold the energy the incremental tangential and rolling springs lose
//! without work, because their stiffness follows the contact while they carry a fixed
//! displacement (Mindlin) or torque (rolling); docs/theory.md, "Energy books of the incremental
//! springs". Spheres that leave the run (`delete_below_m`) take their energy with them into
//! `removed_j`, which the balance counts as well. With an adhesive law the energy the springs
//! held when they let go is booked in `adhesive_j`, apart from `plastic_j` (docs/theory.md §9):
//! the elastic energy then includes the stretched springs of the contacts that hold apart.

use mdr_output::write_atomic;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// One row of the energy books (J, except time and counts).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct EnergyRow {
    /// Simulated time (s).
    pub time_s: f64,
    /// `Σ m v² / 2` (J).
    pub kinetic_translational_j: f64,
    /// `Σ ω·Iω / 2` (J).
    pub kinetic_rotational_j: f64,
    /// `−Σ m g·x` (J).
    pub gravitational_j: f64,
    /// Elastic energy stored in the normal direction of the touching contacts (J).
    pub elastic_normal_j: f64,
    /// Elastic energy stored in the tangential springs of the touching contacts (J).
    pub elastic_tangential_j: f64,
    /// Work dissipated by plasticity since the start (J).
    pub plastic_j: f64,
    /// Work dissipated by friction since the start (J).
    pub friction_j: f64,
    /// Work dissipated by damping since the start (J).
    pub damping_j: f64,
    /// Work done on the particles by moving walls since the start (J).
    pub wall_work_j: f64,
    /// Sum of the books minus the wall work (J): constant in an exact integration.
    pub balance_j: f64,
    /// Touching contacts.
    pub contacts: u64,
    /// Elastic energy stored in the rolling-resistance springs of the touching contacts (J).
    /// (Columns added after `contacts`, so that the earlier ones keep their positions.)
    #[serde(default)]
    pub elastic_rolling_j: f64,
    /// Work dissipated by rolling resistance since the start (J).
    #[serde(default)]
    pub rolling_j: f64,
    /// Energy the tangential (Mindlin) springs lost since the start without work (J; negative
    /// when they gained it): through changes of `k_t = 2 G* a` at a fixed displacement, the
    /// displacement's rescale when the contact shrinks, and what a spring held when its contact
    /// opened. (Added after `rolling_j`.)
    #[serde(default)]
    pub stiffness_tangential_j: f64,
    /// Energy the rolling springs lost since the start without work (J; negative when they
    /// gained it): through changes of `k_r ∝ k_n` (the normal law's tangent stiffness) at a
    /// fixed torque.
    #[serde(default)]
    pub stiffness_rolling_j: f64,
    /// Energy carried out of the run by removed spheres since the start (J): their kinetic and
    /// gravitational energy when `delete_below_m` parks them, less what they have on their spot.
    #[serde(default)]
    pub removed_j: f64,
    /// Adhesive work since the start (J): the energy the adhesive springs held when they let go
    /// (the adhesive hysteresis). The CSV has this column only when some row books adhesive
    /// work.
    #[serde(default)]
    pub adhesive_j: f64,
}

impl EnergyRow {
    /// Fill `balance_j` from the other books.
    pub fn with_balance(mut self) -> Self {
        self.balance_j = self.kinetic_translational_j
            + self.kinetic_rotational_j
            + self.gravitational_j
            + self.elastic_normal_j
            + self.elastic_tangential_j
            + self.plastic_j
            + self.friction_j
            + self.damping_j
            + self.elastic_rolling_j
            + self.rolling_j
            + self.stiffness_tangential_j
            + self.stiffness_rolling_j
            + self.removed_j
            + self.adhesive_j
            - self.wall_work_j;
        self
    }

    /// Total kinetic energy (J).
    pub fn kinetic(&self) -> f64 {
        self.kinetic_translational_j + self.kinetic_rotational_j
    }
}

/// How far the energy balance moved from its start: `balance_j` now less its first value, and
/// that as a fraction of the energy the run moves around (the largest of the initial kinetic
/// and gravitational energies, the work dissipated so far and the kinematic walls' work). The
/// energy guard (`[run] max_energy_drift`) and every run's summary use it.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct BalanceDrift {
    /// `balance_j` now minus its first value (J).
    pub joules: f64,
    /// The energy scale (J).
    pub scale_j: f64,
    /// `joules / scale_j` (0 when both are 0).
    pub fraction: f64,
}

impl BalanceDrift {
    /// The drift from the row `first` to the row `now`.
    pub fn between(first: &EnergyRow, now: &EnergyRow) -> Self {
        // A drum turning a bed that starts at rest near the origin has little initial energy but
        // dissipates all the work the drum does: the dissipated and wall work count too.
        let dissipated =
            now.plastic_j + now.friction_j + now.damping_j + now.rolling_j + now.adhesive_j;
        let scale_j = first
            .kinetic()
            .abs()
            .max(first.gravitational_j.abs())
            .max(dissipated.abs())
            .max(now.wall_work_j.abs());
        let joules = now.balance_j - first.balance_j;
        let fraction = if joules == 0.0 {
            0.0
        } else {
            joules / scale_j.max(1e-300)
        };
        Self {
            joules,
            scale_j,
            fraction,
        }
    }

    /// The same drift against a scale of at least `floor_j` (J). A bed that starts at rest has
    /// almost no energy scale until it moves; the guard measures its drift against at least the
    /// work of lifting every particle by its own diameter, the smallest rearrangement a packing
    /// can make.
    pub fn at_least(self, floor_j: f64) -> Self {
        let scale_j = self.scale_j.max(floor_j);
        let fraction = if self.joules == 0.0 {
            0.0
        } else {
            self.joules / scale_j.max(1e-300)
        };
        Self {
            joules: self.joules,
            scale_j,
            fraction,
        }
    }

    /// The drift over a whole series of rows from its first row with a balance (a finite
    /// `balance_j`: rows taken over from a checkpoint that had none are skipped); `None` when
    /// there is no such row.
    pub fn of(rows: &[EnergyRow]) -> Option<Self> {
        let first = rows.iter().find(|r| r.balance_j.is_finite())?;
        Some(Self::between(first, rows.last()?))
    }
}

/// Write the rows as CSV atomically; the `adhesive_j` column only when a row books adhesive
/// work.
pub fn write_csv(path: &Path, rows: &[EnergyRow]) -> std::io::Result<()> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    for row in rows {
        writer.serialize(row).map_err(std::io::Error::other)?;
    }
    if rows.is_empty() {
        writer
            .write_record([
                "time_s",
                "kinetic_translational_j",
                "kinetic_rotational_j",
                "gravitational_j",
                "elastic_normal_j",
                "elastic_tangential_j",
                "plastic_j",
                "friction_j",
                "damping_j",
                "wall_work_j",
                "balance_j",
                "contacts",
                "elastic_rolling_j",
                "rolling_j",
                "stiffness_tangential_j",
                "stiffness_rolling_j",
                "removed_j",
            ])
            .map_err(std::io::Error::other)?;
    }
    let mut bytes = writer
        .into_inner()
        .map_err(|e| std::io::Error::other(e.to_string()))?;
    if !rows.is_empty() && rows.iter().all(|r| r.adhesive_j == 0.0) {
        // `adhesive_j` is the last field, a plain number: drop it from every line.
        let text = String::from_utf8(bytes).map_err(std::io::Error::other)?;
        bytes = text
            .lines()
            .map(|line| format!("{}\n", &line[..line.rfind(',').unwrap_or(line.len())]))
            .collect::<String>()
            .into_bytes();
    }
    write_atomic(path, &bytes)
}

/// Write the `columns` of the rows (names of [`EnergyRow`]'s fields, in that order) as CSV
/// atomically: a run that keeps only some of the books writes only those.
pub fn write_csv_columns(path: &Path, rows: &[EnergyRow], columns: &[&str]) -> std::io::Result<()> {
    let io = |e: csv::Error| std::io::Error::other(e);
    // Every field through serde once (a default row first, so that the header is written even
    // without rows), then read back and projected onto `columns`.
    let mut full = csv::Writer::from_writer(Vec::new());
    for row in std::iter::once(&EnergyRow::default()).chain(rows) {
        full.serialize(row).map_err(io)?;
    }
    let bytes = full
        .into_inner()
        .map_err(|e| std::io::Error::other(e.to_string()))?;
    let mut reader = csv::Reader::from_reader(bytes.as_slice());
    let names = reader.headers().map_err(io)?.clone();
    let picked = columns
        .iter()
        .map(|c| {
            names.iter().position(|n| n == *c).ok_or_else(|| {
                std::io::Error::other(format!("`{c}` is not a column of the energy books"))
            })
        })
        .collect::<std::io::Result<Vec<usize>>>()?;
    let mut writer = csv::Writer::from_writer(Vec::new());
    writer.write_record(columns).map_err(io)?;
    for record in reader.records().skip(1) {
        let record = record.map_err(io)?;
        writer
            .write_record(picked.iter().map(|&k| record.get(k).unwrap_or("")))
            .map_err(io)?;
    }
    let bytes = writer
        .into_inner()
        .map_err(|e| std::io::Error::other(e.to_string()))?;
    write_atomic(path, &bytes)
}

/// Read rows written by [`write_csv`].
pub fn read_csv(path: &Path) -> Result<Vec<EnergyRow>, String> {
    let mut reader =
        csv::Reader::from_path(path).map_err(|e| format!("{}: {e}", path.display()))?;
    reader
        .deserialize()
        .collect::<Result<Vec<EnergyRow>, _>>()
        .map_err(|e| format!("{}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A CSV written before the rolling columns existed reads with them as zero; a new one
    /// round-trips exactly, with the rolling columns after `contacts`.
    #[test]
    fn old_and_new_csv_read_back() {
        let dir_guard = tempfile::tempdir().unwrap();
        let dir = dir_guard.path().to_path_buf();
        std::fs::create_dir_all(&dir).unwrap();
        let old = dir.join("old.csv");
        std::fs::write(
            &old,
            "time_s,kinetic_translational_j,kinetic_rotational_j,gravitational_j,elastic_normal_j,\
             elastic_tangential_j,plastic_j,friction_j,damping_j,wall_work_j,balance_j,contacts\n\
             0.5,1,2,3,4,5,6,7,8,9,27,3\n",
        )
        .unwrap();
        let rows = read_csv(&old).unwrap();
        assert_eq!(rows.len(), 1);
        assert_eq!(rows[0].contacts, 3);
        assert_eq!(rows[0].elastic_rolling_j, 0.0);
        assert_eq!(rows[0].rolling_j, 0.0);
        assert_eq!(rows[0].stiffness_tangential_j, 0.0);
        assert_eq!(rows[0].stiffness_rolling_j, 0.0);
        assert_eq!(rows[0].removed_j, 0.0);
        assert_eq!(rows[0].with_balance().balance_j, 27.0);

        let row = EnergyRow {
            time_s: 0.25,
            kinetic_translational_j: 1.0,
            elastic_rolling_j: 0.125,
            rolling_j: 0.5,
            stiffness_tangential_j: 0.25,
            stiffness_rolling_j: -0.0625,
            removed_j: 2.0,
            contacts: 2,
            ..EnergyRow::default()
        }
        .with_balance();
        assert_eq!(row.balance_j, 3.8125);
        let new = dir.join("new.csv");
        write_csv(&new, &[row]).unwrap();
        let text = std::fs::read_to_string(&new).unwrap();
        assert!(
            text.starts_with("time_s,")
                && text.lines().next().unwrap().ends_with(
                    "balance_j,contacts,elastic_rolling_j,rolling_j,\
                         stiffness_tangential_j,stiffness_rolling_j,removed_j"
                ),
            "{text}"
        );
        assert_eq!(read_csv(&new).unwrap(), vec![row]);
        std::fs::remove_dir_all(&dir).ok();
    }
}
