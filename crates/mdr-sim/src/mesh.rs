//! Which side of a mesh wall is solid. A triangle mesh read from STL or OBJ is either
//!
//! - **closed** (every edge shared by exactly two triangles): a solid whose particle side is the
//!   side its triangles' normals point to, the normal of a triangle `(a, b, c)` being
//!   `(b − a) × (c − a)` (counter-clockwise seen from the particles' side). A closed mesh whose
//!   neighbouring triangles run a shared edge the same way has no consistent outside and is
//!   refused, naming the triangle; or
//! - **open** (an edge with one triangle, or more than two): a sheet with no inside, touched from
//!   either face (a sphere gets the contact from the face its centre is in front of), as DEM
//!   codes treat STL walls; its winding does not matter.
//!
//! STL files also store a normal per facet; where it points against the winding, the winding
//! decides and the disagreement is reported.

use nalgebra::Vector3;
use std::collections::HashMap;

/// What the topology check found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshTopology {
    /// Every edge is shared by exactly two triangles, wound consistently.
    pub closed: bool,
    /// Volume enclosed by a closed mesh (m³), positive when its normals point outwards (the
    /// particles outside the solid), negative when they point inwards (a closed container);
    /// 0 for an open mesh.
    pub signed_volume: f64,
}

/// The normal `(b − a) × (c − a)` of a triangle (length twice its area).
pub fn winding_normal(vertices: &[Vector3<f64>], t: &[u32; 3]) -> Vector3<f64> {
    let [a, b, c] = t.map(|i| vertices[i as usize]);
    (b - a).cross(&(c - a))
}

/// Check a mesh's topology: closed or open, and for a closed mesh that every pair of
/// neighbouring triangles runs their shared edge in opposite directions. Vertices at the same
/// coordinates are one vertex (STL repeats them per facet). The error names the first
/// triangle (1-based, in file order) wound against a neighbour.
pub fn topology(vertices: &[Vector3<f64>], indices: &[[u32; 3]]) -> Result<MeshTopology, String> {
    let mut id_of: HashMap<[u64; 3], u32> = HashMap::new();
    let canonical: Vec<u32> = vertices
        .iter()
        .enumerate()
        .map(|(i, v)| {
            let key = [v.x, v.y, v.z].map(|c| (c + 0.0).to_bits());
            *id_of.entry(key).or_insert(i as u32)
        })
        .collect();
    // Each undirected edge: the triangles using it and whether they run it from the smaller
    // vertex id to the larger.
    let mut edges: HashMap<(u32, u32), Vec<(usize, bool)>> = HashMap::new();
    for (t, tri) in indices.iter().enumerate() {
        let ids = tri.map(|i| canonical[i as usize]);
        for k in 0..3 {
            let (a, b) = (ids[k], ids[(k + 1) % 3]);
            if a == b {
                continue;
            }
            edges
                .entry((a.min(b), a.max(b)))
                .or_default()
                .push((t, a < b));
        }
    }
    let closed = edges.values().all(|users| users.len() == 2);
    if !closed {
        return Ok(MeshTopology {
            closed: false,
            signed_volume: 0.0,
        });
    }
    // A triangle turned round clashes with all its neighbours: name the one with most clashes.
    let mut clashes: HashMap<usize, (usize, usize)> = HashMap::new();
    for users in edges.values() {
        let ((t, forward_t), (u, forward_u)) = (users[0], users[1]);
        if forward_t == forward_u {
            for (a, b) in [(t, u), (u, t)] {
                let entry = clashes.entry(a).or_insert((0, b));
                entry.0 += 1;
                entry.1 = entry.1.min(b);
            }
        }
    }
    let worst = clashes
        .iter()
        .map(|(&t, &(count, u))| (std::cmp::Reverse(count), t, u))
        .min();
    if let Some((_, t, u)) = worst {
        let corners = indices[t].map(|i| {
            let v = vertices[i as usize];
            format!("({}, {}, {})", v.x, v.y, v.z)
        });
        return Err(format!(
            "the mesh is closed, but triangle {} (corners {}) is wound against its neighbour, \
             triangle {}, across their shared edge: a closed mesh needs every triangle wound the \
             same way, counter-clockwise seen from the particles' side (turn the triangle round \
             in the file, or make the surface open to have it two-sided)",
            t + 1,
            corners.join(", "),
            u + 1
        ));
    }
    // Divergence theorem: V = Σ a · (b × c) / 6 over the triangles.
    let signed_volume = indices
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| vertices[i as usize]);
            a.dot(&b.cross(&c)) / 6.0
        })
        .sum();
    Ok(MeshTopology {
        closed: true,
        signed_volume,
    })
}

/// The facets whose stored normal (STL) points against the normal of their winding: their
/// count and the first one (1-based). Zero stored normals, which STL allows, are skipped.
pub fn facet_normal_disagreements(
    vertices: &[Vector3<f64>],
    indices: &[[u32; 3]],
    stored: &[Vector3<f64>],
) -> Option<(usize, usize)> {
    let against: Vec<usize> = indices
        .iter()
        .zip(stored)
        .enumerate()
        .filter(|(_, (t, n))| winding_normal(vertices, t).dot(n) < 0.0)
        .map(|(i, _)| i + 1)
        .collect();
    against.first().map(|&first| (against.len(), first))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The unit cube's 12 triangles, wound counter-clockwise seen from outside.
    fn cube() -> (Vec<Vector3<f64>>, Vec<[u32; 3]>) {
        let v = (0..8)
            .map(|i| Vector3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
            .collect();
        let t = vec![
            [0, 2, 1],
            [1, 2, 3],
            [4, 5, 6],
            [5, 7, 6],
            [0, 1, 4],
            [1, 5, 4],
            [2, 6, 3],
            [3, 6, 7],
            [0, 4, 2],
            [2, 4, 6],
            [1, 3, 5],
            [3, 7, 5],
        ];
        (v, t)
    }

    #[test]
    fn a_closed_cube_is_closed_with_its_volume_signed_by_its_winding() {
        let (v, mut t) = cube();
        let topo = topology(&v, &t).unwrap();
        assert!(topo.closed);
        assert!((topo.signed_volume - 1.0).abs() < 1e-12, "{topo:?}");
        for tri in &mut t {
            tri.swap(1, 2);
        }
        let inward = topology(&v, &t).unwrap();
        assert!((inward.signed_volume + 1.0).abs() < 1e-12, "{inward:?}");
    }

    #[test]
    fn one_triangle_turned_round_in_a_closed_mesh_is_named() {
        let (v, mut t) = cube();
        t[6].swap(1, 2);
        let e = topology(&v, &t).unwrap_err();
        assert!(e.contains("triangle 7 "), "{e}");
    }

    #[test]
    fn a_mesh_with_a_boundary_is_open_whatever_its_winding() {
        let (v, mut t) = cube();
        t.pop();
        t[0].swap(1, 2);
        let topo = topology(&v, &t).unwrap();
        assert!(!topo.closed);
    }

    #[test]
    fn stored_normals_against_the_winding_are_counted() {
        let (v, t) = cube();
        let mut stored: Vec<_> = t.iter().map(|tri| winding_normal(&v, tri)).collect();
        assert_eq!(facet_normal_disagreements(&v, &t, &stored), None);
        stored[3] = -stored[3];
        stored[9] = -stored[9];
        stored[0] = Vector3::zeros();
        assert_eq!(facet_normal_disagreements(&v, &t, &stored), Some((2, 4)));
    }
}
