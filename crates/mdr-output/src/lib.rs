//! Output utilities shared by every mdr-dem crate that writes files, so that each exists once:
//!
//! - [`write_atomic`] and [`write_atomic_with`]: a file appears whole or not at all (temporary
//!   file in the same directory, `fsync`, rename, `fsync` of the directory where the platform
//!   allows), so neither a reader, a crash nor Ctrl-C ever sees half a file;
//! - [`font::register_plot_font`] (feature `plot`): the font every plot is laid out with,
//!   embedded so that images do not depend on the fonts installed on the machine.

#![warn(missing_docs)]

mod atomic;
#[cfg(feature = "plot")]
pub mod font;

pub use atomic::{write_atomic, write_atomic_with};
