//! Our side of `benches/cross_code.sh`: the validator (Hertz + Mindlin, closed form) on the
//! cross-code cases, one line per case: `case contact_time_s peak_force_n e_n e_t spin_rad_per_s`.
//! Cases: `pair` (two glass spheres, R = 10 mm, 20 m/s head-on) and `wall ANGLE` (aluminium
//! oxide sphere, R = 2.5 mm, 3.9 m/s, μ = 0.092, on a plane of the same material).
//! With arguments `thornton P_Y E NU RHO R V...`: the restitution of the Thornton law (time
//! integration) of a sphere on a plane of the same material at each speed, one line
//! `v e_n yield_speed` per speed; `thornton-liggghts ...` (same arguments) does the same with the
//! unloading branch of LIGGGHTS' `thornton_ning` (`ThorntonUnloading::LiggghtsThorntonNing`).

use mdr_verify::{materials, Backend, Collision, Target};

fn thornton(
    args: &[f64],
    unloading: mdr_contact::normal::ThorntonUnloading,
) -> Result<(), Box<dyn std::error::Error>> {
    let [p_y, e, nu, rho, r, speeds @ ..] = args else {
        return Err("thornton P_Y E NU RHO R V...".into());
    };
    let m = mdr_contact::Material::new(*e, *nu, *rho)?;
    let pair = mdr_contact::ContactPair::sphere_on_half_space(*r, &m, &m)?;
    let law = mdr_impact::NormalSpec::Thornton(
        mdr_contact::normal::Thornton::new(*p_y)?.with_unloading(unloading),
    );
    for &v in speeds {
        let impact = mdr_impact::Impact::new(pair, law, v).steps_per_contact(20_000);
        let out = impact.run()?;
        println!(
            "{v:.9e} {:.9e} {:.9e}",
            out.normal_restitution,
            impact.yield_speed()?
        );
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let unloading = match args.first().map(String::as_str) {
        Some("thornton") => Some(mdr_contact::normal::ThorntonUnloading::Thornton1997),
        Some("thornton-liggghts") => {
            Some(mdr_contact::normal::ThorntonUnloading::LiggghtsThorntonNing)
        }
        _ => None,
    };
    if let Some(unloading) = unloading {
        let numbers = args[1..]
            .iter()
            .map(|a| a.parse::<f64>())
            .collect::<Result<Vec<_>, _>>()?;
        return thornton(&numbers, unloading);
    }
    let glass = materials::glass();
    let pair = Collision {
        steps_per_contact: 20_000,
        ..Collision::head_on(
            0.01,
            glass,
            Target::Sphere {
                radius: 0.01,
                material: glass,
                spin: 0.0,
            },
            20.0,
        )
    };
    let out = pair.run(Backend::ValidatorMindlin)?;
    println!(
        "pair {:.9e} {:.9e} {:.9e} nan nan",
        out.contact_time, out.peak_force, out.normal_restitution
    );
    let alumina = materials::aluminium_oxide();
    for angle in [0.0_f64, 20.0, 45.0, 70.0] {
        let a = angle.to_radians();
        let c = Collision {
            tangential_speed: 3.9 * a.sin(),
            friction: 0.092,
            steps_per_contact: 20_000,
            ..Collision::head_on(
                0.0025,
                alumina,
                Target::Plane { material: alumina },
                3.9 * a.cos(),
            )
        };
        let out = c.run(Backend::ValidatorMindlin)?;
        let et = if angle > 0.0 {
            out.tangential_velocity / c.tangential_speed
        } else {
            f64::NAN
        };
        println!(
            "wall{angle:.0} {:.9e} {:.9e} {:.9e} {:.9e} {:.9e}",
            out.contact_time, out.peak_force, out.normal_restitution, et, out.spin
        );
    }
    Ok(())
}
