//! The LAMMPS data-file format of a bed: `atom_style sphere`, atoms
//! `id type diameter density x y z [ix iy iz]`.

use super::{Bed, BedError};
use nalgebra::Vector3;
use std::io::Write;
use std::path::Path;

impl Bed {
    /// Read a LAMMPS data file (`atom_style sphere`: `id type diameter density x y z [ix iy iz]`).
    /// Atoms are kept in file order.
    pub fn read_lammps(path: &Path) -> Result<Bed, BedError> {
        let name = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|source| BedError::Io {
            path: name.clone(),
            source,
        })?;
        let bad = |line: usize, message: String| BedError::Format {
            path: name.clone(),
            line,
            message,
        };
        let mut lo = [0.0; 3];
        let mut hi = [0.0; 3];
        let mut count = None;
        let mut bed = Bed {
            lo,
            hi,
            diameter: Vec::new(),
            density: Vec::new(),
            position: Vec::new(),
        };
        let mut in_atoms = false;
        for (k, raw) in text.lines().enumerate() {
            let line = raw.split('#').next().unwrap_or("").trim();
            if k == 0 || line.is_empty() {
                if raw.trim_start().starts_with("Atoms") {
                    in_atoms = true;
                }
                continue;
            }
            let words: Vec<&str> = line.split_whitespace().collect();
            if raw.trim_start().starts_with("Atoms") {
                in_atoms = true;
                continue;
            }
            if in_atoms {
                if words[0].parse::<f64>().is_err() {
                    in_atoms = false;
                    continue;
                }
                if words.len() < 7 {
                    return Err(bad(
                        k + 1,
                        format!("atom line has {} fields, expected 7", words.len()),
                    ));
                }
                let v: Vec<f64> = words[2..7]
                    .iter()
                    .map(|w| w.parse::<f64>())
                    .collect::<std::result::Result<_, _>>()
                    .map_err(|e| bad(k + 1, format!("{e}")))?;
                bed.diameter.push(v[0]);
                bed.density.push(v[1]);
                bed.position.push(Vector3::new(v[2], v[3], v[4]));
                continue;
            }
            let parse = |w: &str| {
                w.parse::<f64>()
                    .map_err(|e| bad(k + 1, format!("`{w}`: {e}")))
            };
            if words.len() == 2 && words[1] == "atoms" {
                count = Some(parse(words[0])? as usize);
            } else if words.len() == 4 && words[3].ends_with("hi") {
                let axis = match words[2] {
                    "xlo" => 0,
                    "ylo" => 1,
                    "zlo" => 2,
                    _ => continue,
                };
                lo[axis] = parse(words[0])?;
                hi[axis] = parse(words[1])?;
            }
        }
        bed.lo = lo;
        bed.hi = hi;
        match count {
            Some(c) if c == bed.len() => Ok(bed),
            Some(c) => Err(bad(
                0,
                format!("header says {c} atoms, found {}", bed.len()),
            )),
            None => Err(bad(0, "no `N atoms` header line".into())),
        }
    }

    /// Write a LAMMPS data file (atomically, [`mdr_output::write_atomic_with`]).
    pub fn write_lammps(&self, path: &Path) -> Result<(), BedError> {
        let name = path.display().to_string();
        let io = |source| BedError::Io {
            path: name.clone(),
            source,
        };
        mdr_output::write_atomic_with(path, |temporary| {
            let mut f = std::io::BufWriter::new(std::fs::File::create(temporary)?);
            writeln!(
                f,
                "LAMMPS data file written by mdr-rapier (neighbour_list::bed)\n"
            )?;
            writeln!(f, "{} atoms\n1 atom types\n", self.len())?;
            for (k, axis) in ["x", "y", "z"].iter().enumerate() {
                writeln!(f, "{} {} {axis}lo {axis}hi", self.lo[k], self.hi[k])?;
            }
            writeln!(f, "\nAtoms # sphere\n")?;
            for i in 0..self.len() {
                let p = self.position[i];
                writeln!(
                    f,
                    "{} 1 {} {} {} {} {} 0 0 0",
                    i + 1,
                    self.diameter[i],
                    self.density[i],
                    p.x,
                    p.y,
                    p.z
                )?;
            }
            f.flush()
        })
        .map_err(io)
    }
}
