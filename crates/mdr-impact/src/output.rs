//! CSV tables with fixed headers (a contract: scripts depend on them), measured data input, and
//! atomic file writes with this crate's error type.

use crate::error::{ImpactError, Result};
use crate::impact::ImpactOutcome;
use crate::integrate::TracePoint;
use std::path::Path;

/// Header of `impact curve`.
/// `stuck` is 1 where the sphere stuck (adhesion; `e_n = 0`), else 0.
pub const CURVE_HEADER: [&str; 8] = [
    "v0_m_per_s",
    "e_n",
    "e_n_scaled",
    "d_max_m",
    "d_residual_m",
    "contact_time_s",
    "f_max_n",
    "stuck",
];

/// Header of `impact trace`.
pub const TRACE_HEADER: [&str; 6] = [
    "t_s",
    "d_m",
    "v_m_per_s",
    "f_n",
    "contact_radius_m",
    "plastic_work_j",
];

/// Header of `impact oblique`.
pub const OBLIQUE_HEADER: [&str; 6] = [
    "angle_deg",
    "e_n",
    "e_t",
    "rebound_angle_deg",
    "omega_rad_per_s",
    "stuck",
];

/// Header of measured data for `impact fit` and `--data`.
pub const DATA_HEADER: [&str; 2] = ["v0_m_per_s", "e_n"];

/// A measured coefficient of restitution at one impact speed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measurement {
    /// Impact speed (m/s).
    pub speed: f64,
    /// Measured coefficient of restitution.
    pub restitution: f64,
}

fn table<const N: usize>(header: [&str; N], rows: impl Iterator<Item = [f64; N]>) -> String {
    let mut text = header.join(",");
    text.push('\n');
    for row in rows {
        let cells: Vec<String> = row.iter().map(|x| format!("{x}")).collect();
        text.push_str(&cells.join(","));
        text.push('\n');
    }
    text
}

/// 1 for a stuck impact, 0 otherwise.
fn stuck_flag(outcome: &ImpactOutcome) -> f64 {
    if outcome.stuck {
        1.0
    } else {
        0.0
    }
}

/// The `impact curve` table: one row per outcome, `e_n_scaled = scale · e_n`.
pub fn curve_csv(outcomes: &[ImpactOutcome], scale: f64) -> String {
    table(
        CURVE_HEADER,
        outcomes.iter().map(|o| {
            [
                o.speed,
                o.normal_restitution,
                scale * o.normal_restitution,
                o.max_overlap,
                o.residual_overlap,
                o.contact_time,
                o.peak_force,
                stuck_flag(o),
            ]
        }),
    )
}

/// The `impact trace` table.
pub fn trace_csv(points: &[TracePoint]) -> String {
    table(
        TRACE_HEADER,
        points.iter().map(|p| {
            [
                p.time,
                p.overlap,
                p.velocity,
                p.force,
                p.contact_radius,
                p.plastic_work,
            ]
        }),
    )
}

/// The `impact oblique` table.
pub fn oblique_csv(outcomes: &[ImpactOutcome]) -> String {
    table(
        OBLIQUE_HEADER,
        outcomes.iter().map(|o| {
            [
                o.angle_degrees,
                o.normal_restitution,
                o.tangential_restitution.unwrap_or(f64::NAN),
                o.rebound_angle_degrees,
                o.spin,
                stuck_flag(o),
            ]
        }),
    )
}

/// Write `bytes` to `path` atomically ([`mdr_output::write_atomic`]: temporary file, `fsync`,
/// rename). Missing parent directories are created.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    mdr_output::write_atomic(path, bytes).map_err(|source| ImpactError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Read measured `(v0, e)` pairs from a CSV file with header `v0_m_per_s,e_n`.
pub fn read_measurements(path: &Path) -> Result<Vec<Measurement>> {
    let bad = |reason: String| ImpactError::Csv {
        path: path.to_path_buf(),
        reason,
    };
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .from_path(path)
        .map_err(|e| match e.into_kind() {
            csv::ErrorKind::Io(source) => ImpactError::Io {
                path: path.to_path_buf(),
                source,
            },
            other => bad(format!("{other:?}")),
        })?;
    let header = reader.headers().map_err(|e| bad(e.to_string()))?.clone();
    let column = |name: &str| {
        header.iter().position(|h| h == name).ok_or_else(|| {
            bad(format!(
                "missing column `{name}` (expected header `{}`)",
                DATA_HEADER.join(",")
            ))
        })
    };
    let (speed_column, restitution_column) = (column(DATA_HEADER[0])?, column(DATA_HEADER[1])?);
    let mut data = Vec::new();
    for (index, record) in reader.records().enumerate() {
        let record = record.map_err(|e| bad(e.to_string()))?;
        let line = index + 2;
        let number = |col: usize, name: &str| -> Result<f64> {
            let text = record.get(col).unwrap_or("");
            text.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| {
                    bad(format!(
                        "line {line}: `{name}` = `{text}` is not a finite number"
                    ))
                })
        };
        let speed = number(speed_column, DATA_HEADER[0])?;
        let restitution = number(restitution_column, DATA_HEADER[1])?;
        if speed <= 0.0 {
            return Err(bad(format!(
                "line {line}: v0_m_per_s = {speed} must be > 0"
            )));
        }
        if !(0.0..=1.5).contains(&restitution) {
            return Err(bad(format!(
                "line {line}: e_n = {restitution} must lie in [0, 1.5]"
            )));
        }
        data.push(Measurement { speed, restitution });
    }
    Ok(data)
}
