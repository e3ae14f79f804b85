//! The headline time series as CSV.

use super::HeadlineSample;
use std::path::Path;

/// Write `samples` as CSV: `time_s` and one column per name in `names`; nothing when `names` is
/// empty (a scene without series).
pub(super) fn write_series_csv(
    path: &Path,
    names: &[&str],
    samples: &[HeadlineSample],
) -> std::io::Result<()> {
    if names.is_empty() {
        return Ok(());
    }
    let mut text = format!("time_s,{}\n", names.join(","));
    for s in samples {
        text.push_str(&format!("{:.9e}", s.time));
        for v in &s.values {
            text.push_str(&format!(",{v}"));
        }
        text.push('\n');
    }
    mdr_output::write_atomic(path, text.as_bytes())
}
