//! Particle frames as VTK XML PolyData (`.vtp`, one vertex per sphere, through `vtkio`), the
//! optional contact network (one line per touching pair), and the ParaView collection (`.pvd`)
//! that lists the frames with their simulated times.

use mdr_output::write_atomic;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use vtkio::model::{
    Attribute, Attributes, ByteOrder, DataSet, IOBuffer, Piece, PolyDataPiece, Version,
    VertexNumbers, Vtk,
};

/// Per-particle data of one frame (all vectors of equal length).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ParticleFrame {
    /// Centres (m).
    pub position: Vec<[f64; 3]>,
    /// Radii (m).
    pub radius: Vec<f64>,
    /// Velocities (m/s).
    pub velocity: Vec<[f64; 3]>,
    /// Angular velocities (rad/s).
    pub angular_velocity: Vec<[f64; 3]>,
    /// Number of touching contacts.
    pub contacts: Vec<u32>,
    /// Work dissipated by plasticity in this particle's contacts (J; a sphere–sphere contact's
    /// work is split evenly).
    pub plastic_work: Vec<f64>,
    /// Particle index (stable across frames).
    pub id: Vec<u32>,
}

/// The contact network of one frame: one line per touching pair.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ContactFrame {
    /// First end (centre of sphere 1, m).
    pub from: Vec<[f64; 3]>,
    /// Second end (centre of sphere 2, or the contact point on a wall, m).
    pub to: Vec<[f64; 3]>,
    /// Force on sphere 1 (N).
    pub force: Vec<[f64; 3]>,
    /// Normal force magnitude (N).
    pub normal_force: Vec<f64>,
    /// Overlap (m).
    pub overlap: Vec<f64>,
    /// Residual plastic indentation (m).
    pub plastic_indentation: Vec<f64>,
}

fn flat(v: &[[f64; 3]]) -> Vec<f64> {
    v.iter().flatten().copied().collect()
}

fn vtk_of(piece: PolyDataPiece, title: &str) -> Vtk {
    Vtk {
        version: Version::new_xml(1, 0),
        title: title.to_owned(),
        byte_order: ByteOrder::LittleEndian,
        data: DataSet::PolyData {
            meta: None,
            pieces: vec![Piece::Inline(Box::new(piece))],
        },
        file_path: None,
    }
}

fn encode(vtk: Vtk) -> std::io::Result<Vec<u8>> {
    let mut bytes = Vec::new();
    vtk.write_xml(&mut bytes)
        .map_err(|e| std::io::Error::other(format!("VTK encoding failed: {e}")))?;
    Ok(bytes)
}

/// Write a particle frame to `path` (`.vtp`) atomically.
pub fn write_particles(path: &Path, frame: &ParticleFrame) -> std::io::Result<()> {
    let n = frame.position.len() as u64;
    let piece = PolyDataPiece {
        points: IOBuffer::F64(flat(&frame.position)),
        verts: Some(VertexNumbers::XML {
            connectivity: (0..n).collect(),
            offsets: (1..=n).collect(),
        }),
        lines: None,
        polys: None,
        strips: None,
        data: Attributes {
            point: [
                Some(Attribute::scalars("radius_m", 1).with_data(frame.radius.clone())),
                Some(Attribute::vectors("velocity_m_per_s").with_data(flat(&frame.velocity))),
                Some(
                    Attribute::vectors("angular_velocity_rad_per_s")
                        .with_data(flat(&frame.angular_velocity)),
                ),
                Some(Attribute::scalars("contacts", 1).with_data(frame.contacts.clone())),
                // A frame without plastic work per particle (an empty field) leaves it out.
                (frame.plastic_work.len() == frame.position.len()).then(|| {
                    Attribute::scalars("plastic_work_j", 1).with_data(frame.plastic_work.clone())
                }),
                Some(Attribute::scalars("id", 1).with_data(frame.id.clone())),
            ]
            .into_iter()
            .flatten()
            .collect(),
            cell: Vec::new(),
        },
    };
    write_atomic(path, &encode(vtk_of(piece, "mdr-sim particles"))?)
}

/// Write a contact network to `path` (`.vtp`) atomically.
pub fn write_contacts(path: &Path, frame: &ContactFrame) -> std::io::Result<()> {
    let n = frame.from.len() as u64;
    let mut points = Vec::with_capacity(6 * n as usize);
    for (a, b) in frame.from.iter().zip(&frame.to) {
        points.extend_from_slice(a);
        points.extend_from_slice(b);
    }
    let piece = PolyDataPiece {
        points: IOBuffer::F64(points),
        verts: None,
        lines: Some(VertexNumbers::XML {
            connectivity: (0..2 * n).collect(),
            offsets: (1..=n).map(|i| 2 * i).collect(),
        }),
        polys: None,
        strips: None,
        data: Attributes {
            point: Vec::new(),
            cell: vec![
                Attribute::vectors("force_n").with_data(flat(&frame.force)),
                Attribute::scalars("normal_force_n", 1).with_data(frame.normal_force.clone()),
                Attribute::scalars("overlap_m", 1).with_data(frame.overlap.clone()),
                Attribute::scalars("plastic_indentation_m", 1)
                    .with_data(frame.plastic_indentation.clone()),
            ],
        },
    };
    write_atomic(path, &encode(vtk_of(piece, "mdr-sim contacts"))?)
}

/// Read a particle frame written by [`write_particles`] (for tests and post-processing).
pub fn read_particles(path: &Path) -> Result<ParticleFrame, String> {
    let vtk = Vtk::import(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let DataSet::PolyData { pieces, .. } = vtk.data else {
        return Err(format!("{}: not PolyData", path.display()));
    };
    let Some(Piece::Inline(piece)) = pieces.into_iter().next() else {
        return Err(format!("{}: no inline piece", path.display()));
    };
    let f64s = |b: &IOBuffer| -> Vec<f64> { b.clone().cast_into::<f64>().unwrap_or_default() };
    let triples =
        |v: Vec<f64>| -> Vec<[f64; 3]> { v.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect() };
    let mut frame = ParticleFrame {
        position: triples(f64s(&piece.points)),
        ..Default::default()
    };
    for attribute in &piece.data.point {
        let Attribute::DataArray(array) = attribute else {
            continue;
        };
        let values = f64s(&array.data);
        match array.name.as_str() {
            "radius_m" => frame.radius = values,
            "velocity_m_per_s" => frame.velocity = triples(values),
            "angular_velocity_rad_per_s" => frame.angular_velocity = triples(values),
            "contacts" => frame.contacts = values.iter().map(|&v| v as u32).collect(),
            "plastic_work_j" => frame.plastic_work = values,
            "id" => frame.id = values.iter().map(|&v| v as u32).collect(),
            _ => {}
        }
    }
    Ok(frame)
}

/// One entry of a ParaView collection.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CollectionEntry {
    /// Simulated time (s).
    pub time: f64,
    /// File, relative to the `.pvd`.
    pub file: PathBuf,
    /// Part index (0 particles, 1 contact network).
    pub part: u32,
}

/// Write a `.pvd` collection atomically.
pub fn write_collection(path: &Path, entries: &[CollectionEntry]) -> std::io::Result<()> {
    let mut s = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n",
    );
    for e in entries {
        let _ = writeln!(
            s,
            "    <DataSet timestep=\"{:.9e}\" group=\"\" part=\"{}\" file=\"{}\"/>",
            e.time,
            e.part,
            e.file.display()
        );
    }
    s.push_str("  </Collection>\n</VTKFile>\n");
    write_atomic(path, s.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn particle_frame_reads_back() {
        let dir_guard = tempfile::tempdir().unwrap();
        let dir = dir_guard.path().to_path_buf();
        let path = dir.join("f.vtp");
        let frame = ParticleFrame {
            position: vec![[0.0, 1.0, 2.0], [3.5, -4.0, 1e-3]],
            radius: vec![1e-3, 2e-3],
            velocity: vec![[0.1, 0.2, 0.3], [-1.0, 0.0, 0.0]],
            angular_velocity: vec![[0.0, 0.0, 5.0], [1.0, 2.0, 3.0]],
            contacts: vec![0, 3],
            plastic_work: vec![0.0, 1.5e-9],
            id: vec![0, 1],
        };
        write_particles(&path, &frame).unwrap();
        let back = read_particles(&path).unwrap();
        assert_eq!(back, frame);
        let net = ContactFrame {
            from: vec![[0.0; 3]],
            to: vec![[1.0, 0.0, 0.0]],
            force: vec![[1.0, 2.0, 3.0]],
            normal_force: vec![3.7],
            overlap: vec![1e-6],
            plastic_indentation: vec![2e-7],
        };
        write_contacts(&dir.join("c.vtp"), &net).unwrap();
        assert!(Vtk::import(dir.join("c.vtp")).is_ok());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
