//! The scene validation of `[[walls]]` held to hand-written scenes: `segments`' range, a box's
//! bounds, the default thicknesses of every container, the orifice against its plate, a mesh
//! file, rotation, removal and the pieces stored relative to the rotation centre, and the
//! initial-overlap check of spheres against spheres and walls at its allowance and its limit of
//! six errors; each with the error (key and text) or the geometry it must give. Parsing only: no
//! scene is run.
//! Each test fails with the mutants of the validation it is written for (docs/verification.md
//! §5 names them).

mod common;

use mdr_sim::scene::validate::parse_scene;
use mdr_sim::scene::{Problem, Problems, Scene, Severity};
use mdr_sim::walls::WallPiece;
use nalgebra::{UnitQuaternion, Vector3};

/// The column's `[run]`, gravity, material `grain` and MDR contact, one group of spheres read
/// from `spheres.csv` with the lines `group_extra`, and `walls`.
fn scene(group_extra: &str, walls: &str) -> String {
    let text = common::column(2, 2, 0.01, 0.0, "");
    let head = &text[..text.find("[[particles]]").unwrap()];
    format!(
        "{head}[[particles]]\nmaterial = \"grain\"\nplacement = \"csv\"\nfile = \"spheres.csv\"\n\
         {group_extra}\n{walls}"
    )
}

/// `text` parsed as `scene.toml` beside `spheres.csv` (rows `[x, y, z, radius]`, m) and `files`
/// (name, contents) in a fresh directory, whose path comes back too.
fn parse_with(
    spheres: &[[f64; 4]],
    files: &[(&str, &str)],
    text: &str,
) -> (common::TempDir, Result<Scene, Problems>) {
    let dir = common::temp_dir("walls");
    let mut csv = String::from("x_m,y_m,z_m,radius_m\n");
    for [x, y, z, r] in spheres {
        csv.push_str(&format!("{x:?},{y:?},{z:?},{r:?}\n"));
    }
    common::write(&dir, "spheres.csv", &csv);
    for (name, contents) in files {
        common::write(&dir, name, contents);
    }
    let path = common::write(&dir, "scene.toml", text);
    let result = parse_scene(&path, text);
    (dir, result)
}

/// One sphere of radius 2 mm at `(0, 0, 5 cm)`, inside every wall of these tests.
const SPHERE: [f64; 4] = [0.0, 0.0, 0.05, 0.002];

fn parse(spheres: &[[f64; 4]], text: &str) -> Result<Scene, Problems> {
    parse_with(spheres, &[], text).1
}

fn taken(spheres: &[[f64; 4]], text: &str) -> Scene {
    parse(spheres, text).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

fn errors(spheres: &[[f64; 4]], text: &str) -> Vec<Problem> {
    let problems = parse(spheres, text)
        .err()
        .unwrap_or_else(|| panic!("taken:\n{text}"));
    problems.errors().cloned().collect()
}

/// The scene's only error; panics when it is taken or has other errors.
fn the_error(spheres: &[[f64; 4]], text: &str) -> Problem {
    let errors = errors(spheres, text);
    assert_eq!(errors.len(), 1, "{errors:#?}");
    errors.into_iter().next().unwrap()
}

fn wall(kind: &str, keys: &str) -> String {
    format!("[[walls]]\nkind = \"{kind}\"\nmaterial = \"grain\"\n{keys}\n")
}

/// A plane through `(0, 0, z)` facing up.
fn floor(z: f64) -> String {
    wall(
        "plane",
        &format!("point_m = [0.0, 0.0, {z:?}]\nnormal = [0.0, 0.0, 1.0]"),
    )
}

/// A box whose inside is `[−5, 5] × [−10, 10] × [0, 30]` cm (extents 0.1, 0.2 and 0.3 m), with
/// `extra` lines.
fn open_box(extra: &str) -> String {
    wall(
        "box",
        &format!("min_m = [-0.05, -0.1, 0.0]\nmax_m = [0.05, 0.1, 0.3]\n{extra}"),
    )
}

/// A cylinder of radius 3 cm about the z axis through `(0, 0, 5 cm)`, 10 cm long, and `extra`.
fn cylinder(extra: &str) -> String {
    wall(
        "cylinder",
        &format!("center_m = [0.0, 0.0, 0.05]\nradius_m = 0.03\nlength_m = 0.1\n{extra}"),
    )
}

fn cuboid(piece: &WallPiece) -> (Vector3<f64>, UnitQuaternion<f64>, Vector3<f64>) {
    match piece {
        WallPiece::Cuboid {
            center,
            rotation,
            half_extents,
        } => (*center, *rotation, *half_extents),
        other => panic!("expected a cuboid, got {other:?}"),
    }
}

fn hull(piece: &WallPiece) -> &[Vector3<f64>] {
    match piece {
        WallPiece::ConvexHull { points } => points,
        other => panic!("expected a convex hull, got {other:?}"),
    }
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-15
}

/// `segments` lies in `[3, 4096]` (docs/user-guide.md): 2 and 4097 are refused at the key, 3
/// and 4096 give a cylinder of that many slabs.
#[test]
fn segments_lie_in_three_to_4096() {
    for n in [2, 4097] {
        let e = the_error(&[SPHERE], &scene("", &cylinder(&format!("segments = {n}"))));
        assert_eq!(e.key, "walls[0].segments");
        assert_eq!(
            e.message,
            format!("= {n} is outside the allowed range [3, 4096]")
        );
    }
    for n in [3, 4096] {
        let s = taken(&[SPHERE], &scene("", &cylinder(&format!("segments = {n}"))));
        assert_eq!(s.walls[0].pieces.len(), n);
    }
}

/// A box's inside needs `max_m > min_m` in every component; five slabs with an open top (the
/// default), six closed; the slabs' default thickness is a tenth of the smallest inside extent
/// (here 0.1 m: 1 cm, with `min_m` away from the origin so that `max + min` differs from
/// `max − min`), each slab's inner face on the inside.
#[test]
fn a_box_needs_its_bounds_in_order_and_defaults_to_a_tenth_of_its_smallest_extent() {
    let text =
        scene("", &open_box("")).replace("max_m = [0.05, 0.1, 0.3]", "max_m = [0.05, -0.1, 0.3]");
    let e = the_error(&[SPHERE], &text);
    assert_eq!(e.key, "walls[0].max_m");
    assert_eq!(e.message, "must exceed min_m in every component");

    let s = taken(&[SPHERE], &scene("", &open_box("")));
    assert_eq!(s.walls[0].pieces.len(), 5);
    // The first slab closes the side x = min_m[0] = −0.05 m.
    let (center, _, half) = cuboid(&s.walls[0].pieces[0]);
    assert!(close(2.0 * half.x, 0.01), "{half:?}");
    assert!(close(center.x + half.x, -0.05), "{center:?}");
    let s = taken(&[SPHERE], &scene("", &open_box("open_top = false")));
    assert_eq!(s.walls[0].pieces.len(), 6);
    let s = taken(&[SPHERE], &scene("", &open_box("thickness_m = 0.004")));
    let (_, _, half) = cuboid(&s.walls[0].pieces[0]);
    assert!(close(2.0 * half.x, 0.004), "{half:?}");
}

/// A cylinder's slabs are `radius_m / 5` thick by default (6 mm for a radius of 3 cm), their
/// inner faces tangent to the circle.
#[test]
fn a_cylinder_defaults_to_a_fifth_of_its_radius() {
    let s = taken(&[SPHERE], &scene("", &cylinder("")));
    assert_eq!(s.walls[0].pieces.len(), 48);
    // The slab at φ = 0 lies along +x.
    let (center, _, half) = cuboid(&s.walls[0].pieces[0]);
    assert!(close(2.0 * half.x, 0.006), "{half:?}");
    assert!(close(center.x - half.x, 0.03), "{center:?}");
    assert!(close(half.z, 0.05), "{half:?}");
}

/// A cone's pieces are the larger radius / 10 thick across the axis by default
/// (docs/user-guide.md): radii 3 and 6 cm give 6 mm, so the outer corners at the bottom stand
/// at `(r + t)/r = 1.2` times the inner ones' distance from the axis.
#[test]
fn a_cone_defaults_to_a_tenth_of_its_larger_radius() {
    let cone = wall(
        "cone",
        "center_m = [0.0, 0.0, 0.0]\nradius_m = 0.03\ntop_radius_m = 0.06\nlength_m = 0.1",
    );
    let s = taken(&[SPHERE], &scene("", &cone));
    let points = hull(&s.walls[0].pieces[0]);
    let from_axis = |p: &Vector3<f64>| p.x.hypot(p.y);
    // At the bottom (z = 0): the inner corners, then the outer ones.
    assert_eq!((points[0].z, points[2].z), (0.0, 0.0));
    let ratio = from_axis(&points[2]) / from_axis(&points[0]);
    assert!((ratio - 1.2).abs() < 1e-14, "{ratio}");
}

/// The orifice must be narrower than the plate (`orifice_diameter_m < 2 outer_radius_m`,
/// refused at equality); the plate is `outer_radius_m / 10` thick by default, its top face at
/// `center_m`.
#[test]
fn an_orifice_plate_needs_a_hole_inside_it_and_defaults_to_a_tenth_of_its_radius() {
    let plate = |hole: f64| {
        wall(
            "orifice_plate",
            &format!(
                "center_m = [0.0, 0.0, 0.0]\nouter_radius_m = 0.02\norifice_diameter_m = {hole:?}"
            ),
        )
    };
    let e = the_error(&[SPHERE], &scene("", &plate(0.04)));
    assert_eq!(e.key, "walls[0].orifice_diameter_m");
    assert_eq!(
        e.message,
        "= 0.04 must be smaller than the plate's diameter 2 × outer_radius_m = 0.04"
    );
    let s = taken(&[SPHERE], &scene("", &plate(0.039)));
    let points = hull(&s.walls[0].pieces[0]);
    let bottom = points.iter().map(|p| p.z).fold(f64::INFINITY, f64::min);
    let top = points.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max);
    assert_eq!(top, 0.0);
    assert!(close(bottom, -0.002), "{bottom}");
}

/// A flat square of side 12.5 cm at z = 0 in ASCII STL (two triangles, normals +z), its corners
/// exact in the file's single precision.
const SQUARE_STL: &str = "solid floor
  facet normal 0 0 1
    outer loop
      vertex -0.0625 -0.0625 0
      vertex 0.0625 -0.0625 0
      vertex 0.0625 0.0625 0
    endloop
  endfacet
  facet normal 0 0 1
    outer loop
      vertex -0.0625 -0.0625 0
      vertex 0.0625 0.0625 0
      vertex -0.0625 0.0625 0
    endloop
  endfacet
endsolid floor
";

/// A mesh file is scaled about the origin and then moved by `offset_m`; a missing one is one
/// error at `file`, naming it.
#[test]
fn a_mesh_wall_is_read_scaled_and_moved_and_a_missing_file_is_one_error() {
    let mesh = wall(
        "mesh",
        "file = \"floor.stl\"\nscale = 2.0\noffset_m = [0.0, 0.0, -0.01]",
    );
    let (_dir, result) = parse_with(&[SPHERE], &[("floor.stl", SQUARE_STL)], &scene("", &mesh));
    let s = result.unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.walls.len(), 1);
    match &s.walls[0].pieces[..] {
        [WallPiece::TriMesh { vertices, .. }] => {
            for v in vertices {
                assert_eq!(
                    (v.x.abs(), v.y.abs(), v.z),
                    (0.125, 0.125, -0.01),
                    "{vertices:?}"
                );
            }
        }
        other => panic!("expected one triangle mesh, got {other:?}"),
    }

    let missing = mesh.replace("floor.stl", "missing.stl");
    let (dir, result) = parse_with(&[SPHERE], &[], &scene("", &missing));
    let errors: Vec<Problem> = result.unwrap_err().errors().cloned().collect();
    assert_eq!(errors.len(), 1, "{errors:#?}");
    assert_eq!(errors[0].key, "walls[0].file");
    assert_eq!(
        errors[0].message,
        format!("file `{}` not found", dir.join("missing.stl").display())
    );
}

/// The inside of the box of [`open_box`] seen from the rotation centre `c` (world − c): its
/// first slab's inner face at `x = −0.05 − c_x`.
fn rotating_box(center: [f64; 3], extra: &str) -> String {
    open_box(&format!(
        "angular_velocity_rad_per_s = [0.0, 0.0, 1.0]\nrotation_center_m = {center:?}\n{extra}"
    ))
}

/// A rotating wall keeps its pieces relative to its rotation centre (the body's origin), and the
/// placement check measures the spheres from there: a sphere 4 cm inside the box's side is
/// taken, one across its floor refused.
#[test]
fn a_rotating_wall_is_stored_relative_to_its_rotation_centre() {
    let s = taken(
        &[[0.01, 0.0, 0.05, 0.002]],
        &scene("", &rotating_box([0.02, 0.0, 0.0], "")),
    );
    let w = &s.walls[0];
    assert_eq!(w.origin, Vector3::new(0.02, 0.0, 0.0));
    assert_eq!(w.angular_velocity, Some(Vector3::z()));
    let (center, _, half) = cuboid(&w.pieces[0]);
    assert!(close(center.x + half.x, -0.05 - 0.02), "{center:?}");

    let errors = errors(
        &[[0.01, 0.0, 0.001, 0.002]],
        &scene("", &rotating_box([0.02, 0.0, 0.0], "")),
    );
    assert_eq!(errors.len(), 1, "{errors:#?}");
    assert_eq!(errors[0].key, "walls[0]");

    // Without a rotation centre the body's origin is the world's.
    let s = taken(
        &[SPHERE],
        &scene(
            "",
            &open_box("angular_velocity_rad_per_s = [0.0, 0.0, 1.0]"),
        ),
    );
    assert_eq!(s.walls[0].origin, Vector3::zeros());
}

/// An exact surface of a rotating wall is stored relative to the rotation centre too.
#[test]
fn a_rotating_exact_cylinder_is_stored_relative_to_its_rotation_centre() {
    let text = scene(
        "",
        &cylinder(
            "exact_surface = true\nangular_velocity_rad_per_s = [0.0, 0.0, 2.0]\n\
             rotation_center_m = [0.0, 0.0, 0.05]",
        ),
    );
    let s = taken(&[SPHERE], &text);
    let revolution = s.walls[0].revolution.as_ref().expect("an exact surface");
    assert_eq!(revolution.center, Vector3::zeros());
    assert_eq!(revolution.axis, Vector3::z());
    assert_eq!(revolution.profile, vec![(0.03, -0.05), (0.03, 0.05)]);
    let moved = text.replace(
        "center_m = [0.0, 0.0, 0.05]\nradius_m",
        "center_m = [0.01, 0.0, 0.05]\nradius_m",
    );
    let s = taken(&[SPHERE], &moved);
    let revolution = s.walls[0].revolution.as_ref().expect("an exact surface");
    assert_eq!(revolution.center, Vector3::new(0.01, 0.0, 0.0));
}

/// `rotation_center_m` needs `angular_velocity_rad_per_s`; a plane cannot rotate; a wall may be
/// removed (`removed_at_s`) unless it rotates: each refusal one error at its key.
#[test]
fn rotation_and_removal_keys_are_refused_where_they_do_not_apply() {
    let e = the_error(
        &[SPHERE],
        &scene("", &open_box("rotation_center_m = [0.0, 0.0, 0.0]")),
    );
    assert_eq!(e.key, "walls[0].rotation_center_m");
    assert_eq!(
        e.message,
        "is used only with angular_velocity_rad_per_s: remove it"
    );

    let spinning_floor = floor(0.0) + "angular_velocity_rad_per_s = [0.0, 0.0, 1.0]\n";
    let e = the_error(&[SPHERE], &scene("", &spinning_floor));
    assert_eq!(e.key, "walls[0].angular_velocity_rad_per_s");
    assert_eq!(e.message, "a plane cannot rotate (use a box or a mesh)");

    let s = taken(&[SPHERE], &scene("", &open_box("removed_at_s = 0.5")));
    assert_eq!(s.walls[0].removed_at, Some(0.5));
    assert_eq!(s.walls[0].angular_velocity, None);
    let e = the_error(
        &[SPHERE],
        &scene("", &rotating_box([0.0, 0.0, 0.0], "removed_at_s = 0.5")),
    );
    assert_eq!(e.key, "walls[0].removed_at_s");
    assert_eq!(
        e.message,
        "a rotating wall cannot be removed: remove one of removed_at_s and angular_velocity_rad_per_s"
    );
}

/// A sphere may reach into a wall by its group's `max_initial_overlap_fraction` of its radius
/// (default 0.01): a sphere of 2 mm over a floor with the fraction 0.5 is taken with its centre
/// at 1 mm (exactly at the allowance, which is exact in binary) or 1.5 mm and refused at 0.999 mm
/// with the overlap `r − z`; with the default, taken at 1.99 mm and refused at 1.97 mm.
#[test]
fn a_sphere_may_reach_into_a_wall_by_its_allowance() {
    let half = "max_initial_overlap_fraction = 0.5";
    for z in [0.001, 0.0015] {
        taken(&[[0.0, 0.0, z, 0.002]], &scene(half, &floor(0.0)));
    }
    let e = the_error(&[[0.0, 0.0, 0.000999, 0.002]], &scene(half, &floor(0.0)));
    assert_eq!(e.key, "walls[0]");
    assert_eq!(
        e.message,
        "initial placement: particle 0 (group 0, centre [0.0, 0.0, 0.000999] m, radius 2.000e-3 m) \
         overlaps this wall by 1.001e-3 m"
    );
    taken(&[[0.0, 0.0, 0.00199, 0.002]], &scene("", &floor(0.0)));
    let e = the_error(&[[0.0, 0.0, 0.00197, 0.002]], &scene("", &floor(0.0)));
    assert_eq!(e.key, "walls[0]");
}

/// Two spheres of 2 mm with `max_initial_overlap_fraction = 0.1` may overlap by 0.2 mm: taken at
/// 0.18 mm, refused at 0.22 mm naming both and the allowance.
#[test]
fn two_spheres_may_overlap_by_their_allowance() {
    let tenth = "max_initial_overlap_fraction = 0.1";
    let pair = |dx: f64| [SPHERE, [dx, 0.0, 0.05, 0.002]];
    taken(&pair(0.00382), &scene(tenth, ""));
    let e = the_error(&pair(0.00378), &scene(tenth, ""));
    assert_eq!(e.key, "particles[0]");
    assert_eq!(
        e.message,
        "initial placement overlaps: particle 0 (group 0) and particle 1 (group 0) overlap by \
         2.200e-4 m, more than 10% of the smaller radius (max_initial_overlap_fraction)"
    );
}

/// The overlap check runs on every scene without an error, a scene with only a warning included,
/// and on no scene that already has an error (whose overlaps would only add to its errors).
#[test]
fn the_overlap_check_runs_on_the_scenes_without_errors() {
    let tenth = "max_initial_overlap_fraction = 0.1";
    let pair = [SPHERE, [0.00378, 0.0, 0.05, 0.002]];
    let base = scene(tenth, "");
    assert!(base.contains("duration_s = 0.01\n"), "{base}");
    // A run shorter than its output interval: a warning, and the overlap still refused.
    let short = base.replace("duration_s = 0.01\n", "duration_s = 0.001\n");
    let problems = parse(&pair, &short).unwrap_err();
    assert!(
        problems
            .0
            .iter()
            .any(|p| p.severity == Severity::Warning && p.key == "run.output_interval_s"),
        "{problems}"
    );
    let e = the_error(&pair, &short);
    assert!(e.message.starts_with("initial placement overlaps"), "{e:?}");
    // A negative duration: that error alone.
    let negative = base.replace("duration_s = 0.01\n", "duration_s = -1.0\n");
    assert_eq!(the_error(&pair, &negative).key, "run.duration_s");
}

/// The overlap check stops at six errors: a row of eight spheres of 2 mm, 3.6 mm apart (seven
/// pairs overlapping by 0.4 mm), gives six; one sphere through seven floors gives six, one per
/// wall, for the first six walls.
#[test]
fn the_overlap_check_reports_at_most_six() {
    let row: Vec<[f64; 4]> = (0..8)
        .map(|i| [0.0036 * i as f64, 0.0, 0.05, 0.002])
        .collect();
    let pairs = errors(&row, &scene("", ""));
    assert_eq!(pairs.len(), 6, "{pairs:#?}");
    assert!(pairs.iter().all(|e| e.key == "particles[0]"), "{pairs:#?}");

    let floors = floor(0.0).repeat(7);
    let walls = errors(&[[0.0, 0.0, 0.001, 0.002]], &scene("", &floors));
    let keys: Vec<&str> = walls.iter().map(|e| e.key.as_str()).collect();
    assert_eq!(
        keys,
        ["walls[0]", "walls[1]", "walls[2]", "walls[3]", "walls[4]", "walls[5]"]
    );
}

/// `WallPiece::translated` moves every kind of piece by the shift and nothing else.
#[test]
fn a_translated_piece_moves_by_the_shift() {
    let shift = Vector3::new(1.0, -2.0, 4.0);
    let p = Vector3::new(0.5, 0.25, -1.0);
    let moved = p + shift;
    assert_eq!(moved, Vector3::new(1.5, -1.75, 3.0));
    let rotation = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 0.5);
    let cases = [
        (
            WallPiece::HalfSpace {
                point: p,
                normal: Vector3::y(),
            },
            WallPiece::HalfSpace {
                point: moved,
                normal: Vector3::y(),
            },
        ),
        (
            WallPiece::Cuboid {
                center: p,
                rotation,
                half_extents: Vector3::new(1.0, 2.0, 3.0),
            },
            WallPiece::Cuboid {
                center: moved,
                rotation,
                half_extents: Vector3::new(1.0, 2.0, 3.0),
            },
        ),
        (
            WallPiece::ConvexHull {
                points: vec![p, Vector3::zeros()],
            },
            WallPiece::ConvexHull {
                points: vec![moved, shift],
            },
        ),
        (
            WallPiece::TriMesh {
                vertices: vec![p, Vector3::zeros(), Vector3::x()],
                indices: vec![[0, 1, 2]],
                closed: false,
            },
            WallPiece::TriMesh {
                vertices: vec![moved, shift, Vector3::new(2.0, -2.0, 4.0)],
                indices: vec![[0, 1, 2]],
                closed: false,
            },
        ),
    ];
    for (piece, expected) in cases {
        assert_eq!(piece.translated(&shift), expected);
    }
}
