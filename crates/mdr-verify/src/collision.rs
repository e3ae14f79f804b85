//! One two-body collision, described once and run on either implementation: the single-impact
//! validator (`mdr-impact`) or the rapier force mode (`mdr-rapier`). The contact law always comes
//! from `mdr-contact`.
//!
//! Frame: `n` is the contact normal pointing from the target (body 2) to the sphere (body 1),
//! `t` the tangential direction of the approach. Spins are about `n × t`… taken with the sign
//! that makes a positive spin "roll forward" along `+t` on the target, so the slip velocity of
//! the contact point of body 1 relative to body 2 is
//! `v_slip = v_t − (R₁ ω₁ + R₂ ω₂)` (`docs/verification.md` §2).

use crate::error::{invalid, Result, VerifyError};
use mdr_contact::normal::MdrElastoPlastic;
use mdr_contact::tangential::Mindlin;
use mdr_contact::{ContactPair, Material};
use mdr_impact::{Impact, Method, NormalSpec, TangentialSpec};
use mdr_rapier::rapier::prelude::*;
use mdr_rapier::{ForceModeStepper, SphereBuilder};

/// What the sphere hits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Target {
    /// A fixed plane.
    Plane {
        /// Its material.
        material: Material,
    },
    /// A free sphere.
    Sphere {
        /// Its radius (m).
        radius: f64,
        /// Its material.
        material: Material,
        /// Its spin before the impact (rad/s, sign convention of the module docs).
        spin: f64,
    },
}

/// Which implementation runs the collision, with which tangential law.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Backend {
    /// The validator with the O(1) Mindlin tangential law (`k_t = 2 G* a`, Coulomb cap).
    ValidatorMindlin,
    /// The validator with the MDR spring bed (normal) and its per-spring stick/slip tangential
    /// law (partial slip), with this many springs.
    ValidatorSpringBed {
        /// Springs across the bed.
        springs: usize,
    },
    /// rapier in force mode with the Mindlin tangential law.
    RapierForce,
}

impl Backend {
    /// Short label for tables and plots.
    pub fn label(&self) -> &'static str {
        match self {
            Self::ValidatorMindlin => "validator, Mindlin",
            Self::ValidatorSpringBed { .. } => "validator, MDR spring bed",
            Self::RapierForce => "rapier force mode, Mindlin",
        }
    }
}

/// One collision: sphere (body 1) against a target (body 2), relative velocities given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Collision {
    /// Radius of the sphere (m).
    pub radius: f64,
    /// Its material.
    pub material: Material,
    /// What it hits.
    pub target: Target,
    /// Normal approach speed of the centres (m/s, > 0).
    pub normal_speed: f64,
    /// Tangential velocity of the sphere's centre relative to the target's (m/s, signed).
    pub tangential_speed: f64,
    /// Spin of the sphere before the impact (rad/s).
    pub spin: f64,
    /// Friction coefficient `μ`.
    pub friction: f64,
    /// The normal law (elastic: [`MdrElastoPlastic::elastic`], which is Hertz).
    pub normal_law: MdrElastoPlastic,
    /// Time steps per Hertz contact time.
    pub steps_per_contact: usize,
}

/// What a collision produced, from the sphere's point of view.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CollisionOutcome {
    /// `e_n = −v_n,out / v_n,in` of the relative normal velocity.
    pub normal_restitution: f64,
    /// Normal impulse on the sphere (N s).
    pub normal_impulse: f64,
    /// Tangential impulse on the sphere along `+t` (N s).
    pub tangential_impulse: f64,
    /// Tangential velocity of the sphere relative to the target after the impact (m/s).
    pub tangential_velocity: f64,
    /// Spin of the sphere after the impact (rad/s).
    pub spin: f64,
    /// Spin of the target sphere after the impact (rad/s); 0 for a plane.
    pub target_spin: f64,
    /// Time from first touch to separation (s).
    pub contact_time: f64,
    /// Largest normal force (N).
    pub peak_force: f64,
    /// Time step used (s).
    pub time_step: f64,
}

impl Collision {
    /// A head-on, spin-free, frictionless elastic collision at `normal_speed` (m/s).
    pub fn head_on(radius: f64, material: Material, target: Target, normal_speed: f64) -> Self {
        Self {
            radius,
            material,
            target,
            normal_speed,
            tangential_speed: 0.0,
            spin: 0.0,
            friction: 0.0,
            normal_law: MdrElastoPlastic::elastic(),
            steps_per_contact: 1000,
        }
    }

    /// The pair quantities (`E*`, `G*`, `R`, `m`).
    pub fn pair(&self) -> Result<ContactPair> {
        Ok(match self.target {
            Target::Plane { material } => {
                ContactPair::sphere_on_half_space(self.radius, &self.material, &material)?
            }
            Target::Sphere {
                radius, material, ..
            } => ContactPair::sphere_on_sphere(self.radius, &self.material, radius, &material)?,
        })
    }

    /// Mass of the sphere (kg).
    pub fn mass(&self) -> f64 {
        self.material.sphere_mass(self.radius)
    }

    /// Spin of the target before the impact (rad/s).
    pub fn target_spin(&self) -> f64 {
        match self.target {
            Target::Plane { .. } => 0.0,
            Target::Sphere { spin, .. } => spin,
        }
    }

    /// Slip velocity of the contact point before the impact (m/s): `v_t − (R₁ω₁ + R₂ω₂)`.
    pub fn slip_velocity(&self) -> f64 {
        self.tangential_speed - self.contact_spin_speed()
    }

    fn contact_spin_speed(&self) -> f64 {
        let target = match self.target {
            Target::Plane { .. } => 0.0,
            Target::Sphere { radius, spin, .. } => radius * spin,
        };
        self.radius * self.spin + target
    }

    fn validate(&self) -> Result<()> {
        for (name, v) in [("radius", self.radius), ("normal_speed", self.normal_speed)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(invalid(name, v, "a finite number > 0"));
            }
        }
        for (name, v) in [
            ("tangential_speed", self.tangential_speed),
            ("spin", self.spin),
            ("target_spin", self.target_spin()),
        ] {
            if !v.is_finite() {
                return Err(invalid(name, v, "a finite number"));
            }
        }
        if self.steps_per_contact < 10 {
            return Err(invalid(
                "steps_per_contact",
                self.steps_per_contact,
                "at least 10",
            ));
        }
        Ok(())
    }

    /// Run on `backend`.
    pub fn run(&self, backend: Backend) -> Result<CollisionOutcome> {
        self.validate()?;
        match backend {
            Backend::ValidatorMindlin => {
                self.run_validator(TangentialSpec::Mindlin, Method::Closed)
            }
            Backend::ValidatorSpringBed { springs } => {
                self.run_validator(TangentialSpec::SpringBed, Method::Springs { springs })
            }
            Backend::RapierForce => self.run_rapier(),
        }
    }

    /// The validator integrates one sphere of the pair's reduced mass `m*` and radius `R*` with
    /// `I* = 0.4 m* R*²`. For two free spheres this is exact: the slip velocity obeys
    /// `d v_slip/dt = F_t (1/m₁ + 1/m₂ + R₁²/I₁ + R₂²/I₂) = 3.5 F_t / m*` in both, with
    /// `R* ω* = R₁ω₁ + R₂ω₂` (`docs/verification.md` §2). The mirror `t → −t` keeps the
    /// validator's angle in `[0, 90)`.
    fn run_validator(
        &self,
        tangential: TangentialSpec,
        method: Method,
    ) -> Result<CollisionOutcome> {
        let pair = self.pair()?;
        let sign = if self.tangential_speed < 0.0 {
            -1.0
        } else {
            1.0
        };
        let vt = sign * self.tangential_speed;
        let spin_star = sign * self.contact_spin_speed() / pair.effective_radius();
        let vn = self.normal_speed;
        let speed = vn.hypot(vt);
        let angle = vt.atan2(vn).to_degrees();
        let outcome = Impact::new(pair, NormalSpec::Mdr(self.normal_law), speed)
            .angle_degrees(angle)
            .spin(spin_star)
            .friction(self.friction)
            .tangential(tangential)
            .method(method)
            .steps_per_contact(self.steps_per_contact)
            .route(mdr_impact::Route::TimeIntegration)
            .run()?;
        let m_star = pair.reduced_mass();
        let e = outcome.normal_restitution;
        let vt_out = sign * outcome.tangential_velocity;
        let jt = m_star * (vt_out - self.tangential_speed);
        Ok(self.outcome_from_impulses(
            e,
            jt,
            outcome.contact_time,
            outcome.peak_force,
            pair.hertz_contact_time(vn) / self.steps_per_contact as f64,
        ))
    }

    fn outcome_from_impulses(
        &self,
        e: f64,
        jt: f64,
        contact_time: f64,
        peak_force: f64,
        time_step: f64,
    ) -> CollisionOutcome {
        let m1 = self.mass();
        let i1 = 0.4 * m1 * self.radius * self.radius;
        let (inv_m2, target_spin) = match self.target {
            Target::Plane { .. } => (0.0, 0.0),
            Target::Sphere {
                radius,
                material,
                spin,
            } => {
                let m2 = material.sphere_mass(radius);
                let i2 = 0.4 * m2 * radius * radius;
                (1.0 / m2, spin - radius * jt / i2)
            }
        };
        let m_star = 1.0 / (1.0 / m1 + inv_m2);
        CollisionOutcome {
            normal_restitution: e,
            normal_impulse: m_star * (1.0 + e) * self.normal_speed,
            tangential_impulse: jt,
            tangential_velocity: self.tangential_speed + jt / m_star,
            spin: self.spin - self.radius * jt / i1,
            target_spin,
            contact_time,
            peak_force,
            time_step,
        }
    }

    /// rapier force mode: normal `+y`, tangential `+x`; a positive spin (rolling forward along
    /// `+x` on a body below) is a negative `z` angular velocity for both bodies.
    fn run_rapier(&self) -> Result<CollisionOutcome> {
        let pair = self.pair()?;
        let vn = self.normal_speed;
        let dt = pair.hertz_contact_time(vn) / self.steps_per_contact as f64;
        let mut world = PhysicsWorld {
            gravity: Vector::ZERO,
            ..Default::default()
        };
        world.integration_parameters.length_unit = 2.0 * self.radius;
        let model = mdr_contact::model::ContactModel::new(self.normal_law)
            .with_tangential(Mindlin::new(self.friction)?);
        let mut stepper = ForceModeStepper::new(model);
        stepper.configure(&mut world.integration_parameters, dt, 0.2 * self.radius)?;
        let ball_material = stepper.particles_mut().insert_material(self.material);
        // Start 2.5 steps of flight apart: the first touch falls inside a step.
        let gap = 2.5 * vn * dt;
        let target = match self.target {
            Target::Plane { material } => {
                let m = stepper.particles_mut().insert_material(material);
                stepper.insert_surface(
                    &mut world,
                    ColliderBuilder::new(SharedShape::halfspace(Vector::Y)),
                    None,
                    m,
                )?;
                None
            }
            Target::Sphere {
                radius,
                material,
                spin,
            } => {
                let m = stepper.particles_mut().insert_material(material);
                let (t, _) = stepper.insert_sphere(
                    &mut world,
                    SphereBuilder::new(radius, m)
                        .translation(Vector::new(0.0, -radius, 0.0))
                        .angvel(Vector::new(0.0, 0.0, -spin)),
                )?;
                Some(t)
            }
        };
        let (ball, _) = stepper.insert_sphere(
            &mut world,
            SphereBuilder::new(self.radius, ball_material)
                .translation(Vector::new(0.0, self.radius + gap, 0.0))
                .linvel(Vector::new(self.tangential_speed, -vn, 0.0))
                .angvel(Vector::new(0.0, 0.0, -self.spin)),
        )?;
        let m1 = self.mass();
        let max_steps = 50 * self.steps_per_contact as u64 + 100;
        let (mut touched, mut contact_steps, mut peak_force) = (false, 0u64, 0.0_f64);
        let mut finished = false;
        for _ in 0..max_steps {
            let before = world.bodies[ball].linvel().y;
            let report = stepper.step(&mut world)?;
            if report.contacts > 0 {
                touched = true;
                contact_steps += 1;
                // Symplectic Euler: the step's velocity change is exactly F dt / m.
                let after = world.bodies[ball].linvel().y;
                peak_force = peak_force.max(m1 * (after - before).abs() / dt);
            } else if touched {
                finished = true;
                break;
            }
        }
        if !finished {
            return Err(VerifyError::NoSeparation { steps: max_steps });
        }
        let b = &world.bodies[ball];
        let (v2, w2, p2) = match target {
            Some(t) => (
                world.bodies[t].linvel(),
                -world.bodies[t].angvel().z,
                world.bodies[t].translation(),
            ),
            None => (Vector::ZERO, 0.0, b.translation() - Vector::Y),
        };
        // Components in the contact frame at separation: two free spheres that slide past each
        // other turn their centre line during the contact (by about v_t t_c / (R₁ + R₂)), and
        // the collision's normal and tangential directions are those of that line.
        let n = (b.translation() - p2).normalize();
        let t = Vector::new(n.y, -n.x, 0.0);
        let rel = b.linvel() - v2;
        let v1_in = Vector::new(self.tangential_speed, -vn, 0.0);
        let e = rel.dot(n) / vn;
        let jt = m1 * (b.linvel() - v1_in).dot(t);
        let mut out = self.outcome_from_impulses(e, jt, contact_steps as f64 * dt, peak_force, dt);
        // Measured, not derived: spins and relative tangential velocity as rapier integrated them.
        out.spin = -b.angvel().z;
        out.target_spin = w2;
        out.tangential_velocity = rel.dot(t);
        Ok(out)
    }
}
