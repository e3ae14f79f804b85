//! Granular column collapse in force mode: a few thousand spheres released from a square column
//! onto a plane spread until they stop. Reports the run-out distance and the final height and
//! writes legacy-VTK frames (points with radius and velocity) for ParaView.
//!
//! Run: `cargo run --release --example column_collapse -- [OUT_DIR] [END_TIME_S]`
//! (defaults: `column_frames`, 1.5 s). Open `OUT_DIR/frame_*.vtk` in ParaView as a series and
//! show the points as spheres ("Point Gaussian", scale by `radius`).
//!
//! The material is soft (E = 1 MPa, glass-like density) so the run takes minutes, not hours: the
//! time step follows the Hertz contact time, which grows as E*^(-2/5).

use mdr_rapier::prelude::*;
use mdr_rapier::rapier::prelude::*;
use mdr_rapier::LawPair as ContactPair;
use rand::{Rng, SeedableRng};
use std::path::{Path, PathBuf};
use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataSet, UnstructuredGridPiece, Version,
    VertexNumbers, Vtk,
};

const SIDE: usize = 10;
const LAYERS: usize = 20;
const RADIUS: f64 = 2.0e-3;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let out = PathBuf::from(args.next().unwrap_or_else(|| "column_frames".into()));
    let end_time: f64 = args.next().map_or(Ok(1.5), |s| s.parse())?;
    std::fs::create_dir_all(&out)?;

    let material = Material::new(1.0e6, 0.3, 2500.0)?;
    let model = ContactModel::new(MdrElastoPlastic::new(5.0e2, 0.37)?)
        .with_tangential(Mindlin::new(0.3)?)
        .with_damping(StiffnessViscous::new(0.2)?);
    let mut stepper = ForceModeStepper::new(model).with_rolling(EpsdRolling::new(0.05)?);
    let m = stepper.particles_mut().insert_material(material);
    let mut world = PhysicsWorld::default();
    world.integration_parameters.length_unit = 2.0 * RADIUS;
    let floor = ColliderBuilder::new(SharedShape::halfspace(Vector::Y));
    stepper.insert_surface(&mut world, floor, None, m)?;

    // A loose square column centred on the y axis.
    let spacing = 2.05 * RADIUS;
    let half = 0.5 * SIDE as f64 * spacing;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
    let mut bodies = Vec::new();
    for layer in 0..LAYERS {
        for i in 0..SIDE {
            for k in 0..SIDE {
                // Alternate layers sit over the hollows of the layer below (a square column of
                // stacked spheres with friction would stand), plus a small random jitter.
                let shift = if layer % 2 == 1 { 0.5 * spacing } else { 0.0 };
                let jitter = 0.02 * RADIUS;
                let centre = Vector::new(
                    -half + spacing * (i as f64 + 0.25) + shift + rng.random_range(-jitter..jitter),
                    RADIUS + spacing * layer as f64 + 1e-4,
                    -half + spacing * (k as f64 + 0.25) + shift + rng.random_range(-jitter..jitter),
                );
                let r = RADIUS * rng.random_range(0.95..1.0);
                let sphere = SphereBuilder::new(r, m).translation(centre);
                bodies.push(stepper.insert_sphere(&mut world, sphere)?.0);
            }
        }
    }
    let height0 = spacing * LAYERS as f64;
    let pair = ContactPair::sphere_on_sphere(RADIUS, &material, RADIUS, &material)?;
    let v_max = (2.0 * 9.81 * height0).sqrt();
    let dt = stable_time_step(&pair, v_max, 50.0)?.time_step;
    stepper.configure(&mut world.integration_parameters, dt, 0.5 * RADIUS)?;
    println!(
        "{} spheres, column {:.1} mm wide and {:.1} mm high, dt = {dt:.2e} s",
        bodies.len(),
        2e3 * half,
        1e3 * height0
    );

    let frame_every = (0.01 / dt).round() as usize;
    let (mut step, mut frame, mut peak) = (0usize, 0usize, 0.0f64);
    let started = std::time::Instant::now();
    while step as f64 * dt < end_time {
        if step % frame_every == 0 {
            write_frame(&out, frame, &world, &bodies)?;
            frame += 1;
        }
        stepper.step(&mut world)?;
        step += 1;
        let ke: f64 = bodies
            .iter()
            .map(|&h| 0.5 * world.bodies[h].mass() * world.bodies[h].linvel().length_squared())
            .sum();
        peak = peak.max(ke);
        if step as f64 * dt > 0.1 && ke < 1e-6 * peak {
            break;
        }
    }
    write_frame(&out, frame, &world, &bodies)?;
    let wall = started.elapsed().as_secs_f64();

    // Run-out: farthest sphere edge from the axis, minus the column half-width; final height:
    // highest sphere top.
    let (mut run_out, mut height) = (0.0f64, 0.0f64);
    for &h in &bodies {
        let x = world.bodies[h].translation();
        run_out = run_out.max(x.x.abs().max(x.z.abs()) + RADIUS);
        height = height.max(x.y + RADIUS);
    }
    println!(
        "simulated {:.3} s in {step} steps ({wall:.1} s wall)",
        step as f64 * dt
    );
    println!(
        "run-out distance: {:.2} mm (from the column edge)",
        1e3 * (run_out - half)
    );
    println!(
        "final height: {:.2} mm (initial {:.2} mm)",
        1e3 * height,
        1e3 * height0
    );
    println!("{} frames in {}", frame + 1, out.display());
    Ok(())
}

/// One legacy-VTK frame: sphere centres as vertex cells with `radius` and `velocity` point data,
/// written to a temporary file and renamed (atomic).
fn write_frame(
    dir: &Path,
    frame: usize,
    world: &PhysicsWorld,
    bodies: &[RigidBodyHandle],
) -> Result<(), Box<dyn std::error::Error>> {
    let mut points = Vec::with_capacity(3 * bodies.len());
    let mut velocity = Vec::with_capacity(3 * bodies.len());
    let mut radius = Vec::with_capacity(bodies.len());
    for &h in bodies {
        let b = &world.bodies[h];
        let (x, v) = (b.translation(), b.linvel());
        points.extend([x.x, x.y, x.z]);
        velocity.extend([v.x, v.y, v.z]);
        let ball = b
            .colliders()
            .first()
            .and_then(|&c| world.colliders[c].shape().as_ball());
        radius.push(ball.map_or(RADIUS, |ball| ball.radius));
    }
    let n = bodies.len() as u32;
    let vtk = Vtk {
        version: Version::new_legacy(4, 2),
        title: format!("column collapse frame {frame}"),
        byte_order: ByteOrder::BigEndian,
        file_path: None,
        data: DataSet::inline(UnstructuredGridPiece {
            points: points.into(),
            cells: Cells {
                cell_verts: VertexNumbers::Legacy {
                    num_cells: n,
                    vertices: (0..n).flat_map(|i| [1, i]).collect(),
                },
                types: vec![CellType::Vertex; n as usize],
            },
            data: Attributes {
                point: vec![
                    Attribute::scalars("radius", 1).with_data(radius),
                    Attribute::vectors("velocity").with_data(velocity),
                ],
                cell: vec![],
            },
        }),
    };
    let path = dir.join(format!("frame_{frame:04}.vtk"));
    let tmp = dir.join(format!(".frame_{frame:04}.vtk.tmp"));
    vtk.write_legacy(std::io::BufWriter::new(std::fs::File::create(&tmp)?))?;
    std::fs::rename(tmp, path)?;
    Ok(())
}
