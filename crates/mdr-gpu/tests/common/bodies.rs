//! The particles of two checkpoints compared: their largest differences, and whether they agree
//! in every bit.

use mdr_sim::run::CheckpointData;

/// The largest difference of the particles' positions, velocities and angular velocities
/// between two checkpoints' bodies (the first `n` bodies: the particles).
pub fn body_differences(a: &CheckpointData, b: &CheckpointData, n: usize) -> [f64; 3] {
    let mut worst = [0.0f64; 3];
    for (x, y) in a.bodies[..n].iter().zip(&b.bodies[..n]) {
        for (k, (u, v)) in [
            (x.translation, y.translation),
            (x.linvel, y.linvel),
            (x.angvel, y.angvel),
        ]
        .into_iter()
        .enumerate()
        {
            let d = (0..3).map(|c| (u[c] - v[c]).powi(2)).sum::<f64>().sqrt();
            worst[k] = worst[k].max(d);
        }
    }
    worst
}

/// Whether two checkpoints' particles agree in every bit.
pub fn same_bits(a: &CheckpointData, b: &CheckpointData, n: usize) -> bool {
    let bits = |v: [f64; 3]| v.map(f64::to_bits);
    a.bodies[..n].iter().zip(&b.bodies[..n]).all(|(x, y)| {
        bits(x.translation) == bits(y.translation)
            && bits(x.linvel) == bits(y.linvel)
            && bits(x.angvel) == bits(y.angvel)
    })
}
