//! Triangle meshes read from STL (binary or ASCII) or OBJ files, and their collision shapes.

use super::WallPiece;
use nalgebra::Vector3;
use std::path::Path;

/// Read a triangle mesh from an STL (binary or ASCII) or OBJ file, scale it and move it.
pub fn read_mesh(path: &Path, scale: f64, offset: Vector3<f64>) -> Result<WallPiece, String> {
    read_mesh_with_notes(path, scale, offset).map(|(piece, _)| piece)
}

/// [`read_mesh`], with what the user should know about the mesh: STL facet normals that point
/// against the winding (the winding decides), and whether the mesh is a closed solid or an open,
/// two-sided sheet. A closed mesh wound inconsistently is refused ([`crate::mesh::topology`]).
pub fn read_mesh_with_notes(
    path: &Path,
    scale: f64,
    offset: Vector3<f64>,
) -> Result<(WallPiece, Vec<String>), String> {
    if std::fs::metadata(path).is_ok_and(|m| m.len() == 0) {
        return Err(format!("{}: the file is empty (0 bytes)", path.display()));
    }
    let mut stored_normals = Vec::new();
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let (vertices, indices): (Vec<Vector3<f64>>, Vec<[u32; 3]>) = match ext.as_deref() {
        Some("stl") => {
            let mut file = std::fs::File::open(path)
                .map_err(|e| format!("cannot open {}: {e}", path.display()))?;
            let mesh = stl_io::read_stl(&mut file)
                .map_err(|e| format!("cannot read STL {}: {e}", path.display()))?;
            stored_normals = mesh
                .faces
                .iter()
                .map(|f| Vector3::new(f.normal[0] as f64, f.normal[1] as f64, f.normal[2] as f64))
                .collect();
            let vertices = mesh
                .vertices
                .iter()
                .map(|v| Vector3::new(v[0] as f64, v[1] as f64, v[2] as f64))
                .collect();
            let indices = mesh
                .faces
                .iter()
                .map(|f| {
                    [
                        f.vertices[0] as u32,
                        f.vertices[1] as u32,
                        f.vertices[2] as u32,
                    ]
                })
                .collect();
            (vertices, indices)
        }
        Some("obj") => {
            let (models, _) = tobj::load_obj(
                path,
                &tobj::LoadOptions {
                    triangulate: true,
                    single_index: true,
                    ..Default::default()
                },
            )
            .map_err(|e| format!("cannot read OBJ {}: {e}", path.display()))?;
            let mut vertices = Vec::new();
            let mut indices = Vec::new();
            for m in models {
                let base = vertices.len() as u32;
                for p in m.mesh.positions.chunks_exact(3) {
                    vertices.push(Vector3::new(p[0] as f64, p[1] as f64, p[2] as f64));
                }
                for t in m.mesh.indices.chunks_exact(3) {
                    indices.push([base + t[0], base + t[1], base + t[2]]);
                }
            }
            (vertices, indices)
        }
        _ => {
            return Err(format!(
                "{}: unknown mesh format (allowed: .stl, .obj)",
                path.display()
            ))
        }
    };
    if indices.is_empty() {
        return Err(format!("{}: the mesh has no triangles", path.display()));
    }
    let n = vertices.len() as u32;
    if indices.iter().flatten().any(|&i| i >= n) {
        return Err(format!(
            "{}: a triangle refers to a missing vertex",
            path.display()
        ));
    }
    let vertices: Vec<_> = vertices.into_iter().map(|v| v * scale + offset).collect();
    if vertices.iter().any(|v| !v.iter().all(|c| c.is_finite())) {
        return Err(format!(
            "{}: a vertex is not a finite number",
            path.display()
        ));
    }
    let topology = crate::mesh::topology(&vertices, &indices)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let mut notes = Vec::new();
    // A negative scale mirrors the mesh and turns its winding round with it.
    if let Some((count, first)) = crate::mesh::facet_normal_disagreements(
        &vertices,
        &indices,
        &stored_normals
            .iter()
            .map(|n| n * scale.signum())
            .collect::<Vec<_>>(),
    ) {
        notes.push(format!(
            "{}: {count} of {} facet normals (the first: facet {first}) point against their \
             triangle's winding; the winding decides (the normal of corners a, b, c is \
             (b − a) × (c − a)){}",
            path.display(),
            indices.len(),
            if topology.closed {
                ", and this closed mesh's particle side is the side its windings' normals point to"
            } else {
                "; this open mesh is two-sided, so neither changes the contacts"
            }
        ));
    }
    Ok((
        WallPiece::TriMesh {
            vertices,
            indices,
            closed: topology.closed,
        },
        notes,
    ))
}

/// The collision shape of a mesh: a closed mesh is oriented (parry's pseudo-normals tell its
/// inside from its outside, the outside being the side its faces' normals point to); an open
/// one is not, so a point's projection is never inside it and a sphere is pushed away from the
/// face its centre is in front of (two-sided).
pub fn trimesh_shape(
    vertices: &[Vector3<f64>],
    indices: &[[u32; 3]],
    closed: bool,
) -> Result<rapier3d_f64::prelude::SharedShape, String> {
    use rapier3d_f64::parry::shape::TriMeshFlags;
    let flags = if closed {
        TriMeshFlags::ORIENTED | TriMeshFlags::MERGE_DUPLICATE_VERTICES
    } else {
        TriMeshFlags::MERGE_DUPLICATE_VERTICES
    };
    rapier3d_f64::prelude::SharedShape::trimesh_with_flags(
        vertices.iter().map(mdr_rapier::convert::to_glam).collect(),
        indices.to_vec(),
        flags,
    )
    .map_err(|e| format!("triangle mesh: {e}"))
}
