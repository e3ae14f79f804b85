//! What the GPU tests share.

/// The box scenes' 27 spheres of radius 2 mm on a 6 mm lattice, each with a fixed
/// pseudo-random velocity of up to 0.5 m/s per component (SplitMix64, the same on every
/// machine), as the particle CSV of a scene.
pub fn box_csv() -> String {
    let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
    let mut next = || {
        // SplitMix64: a fixed sequence, the same on every machine.
        seed = seed.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = seed;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let mut csv = String::from("x_m,y_m,z_m,radius_m,vx_m_per_s,vy_m_per_s,vz_m_per_s\n");
    for k in 0..3 {
        for j in 0..3 {
            for i in 0..3 {
                let at = |n: usize| -0.006 + 0.006 * n as f64;
                let v = [next(), next(), next()];
                csv.push_str(&format!(
                    "{:.6},{:.6},{:.6},0.002,{:.6},{:.6},{:.6}\n",
                    at(i),
                    at(j),
                    0.004 + 0.006 * k as f64,
                    v[0],
                    v[1],
                    v[2]
                ));
            }
        }
    }
    csv
}
