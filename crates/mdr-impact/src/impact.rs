//! One impact: its description ([`Impact`], a builder) and its outcome ([`ImpactOutcome`]).

use crate::energy::energy_route;
use crate::error::{ImpactError, Result};
use crate::integrate::{integrate_normal, integrate_oblique, NormalRun, ObliqueRun, TracePoint};
use crate::law::{Method, NormalSpec, Route, TangentialSpec, BED_HALF_WIDTH_MARGIN};
use mdr_contact::normal::{
    AdhesiveMdr, AdhesiveSpringBed, Hertz, MdrElastoPlastic, MdrState, NormalLaw, NormalModel,
    SpringBed,
};
use mdr_contact::tangential::{Mindlin, SpringBedTangential, TangentialModel};
use mdr_contact::ContactPair;

/// Default number of time steps per Hertz contact time.
pub const DEFAULT_STEPS_PER_CONTACT: usize = 2000;

/// A single impact: a sphere (or two spheres, through the pair's effective radius and reduced
/// mass) meeting at speed `speed`, at `angle` from the normal, with initial spin.
///
/// ```
/// use mdr_impact::{Impact, NormalSpec};
/// use mdr_contact::ContactPair;
/// let outcome = Impact::new(ContactPair::paper_fig2(), NormalSpec::paper(), 1.0).run().unwrap();
/// assert!(outcome.normal_restitution < 1.0 && outcome.normal_restitution > 0.5);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Impact {
    pair: ContactPair,
    normal: NormalSpec,
    method: Method,
    route: Route,
    speed: f64,
    angle_degrees: f64,
    spin: f64,
    friction: f64,
    tangential: TangentialSpec,
    steps_per_contact: usize,
    work_of_adhesion: f64,
}

/// What one impact produced.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactOutcome {
    /// Impact speed (m/s).
    pub speed: f64,
    /// Impact angle from the normal (degrees).
    pub angle_degrees: f64,
    /// Normal coefficient of restitution `e_n = −v_n,out / v_n,in` (eq. 14), raw model value.
    pub normal_restitution: f64,
    /// Tangential coefficient `e_t = |v_t,out| / |v_t,in|` of the centre of mass; `None` for a
    /// head-on impact.
    pub tangential_restitution: Option<f64>,
    /// Tangential centre-of-mass velocity after the impact (m/s), signed along the incoming one.
    pub tangential_velocity: f64,
    /// Rebound angle from the normal (degrees), from the centre-of-mass velocity.
    pub rebound_angle_degrees: f64,
    /// Angular velocity after the impact (rad/s), positive in the sense of rolling forward.
    pub spin: f64,
    /// Largest overlap `d_max` (m).
    pub max_overlap: f64,
    /// Residual (plastic) depth after separation (m).
    pub residual_overlap: f64,
    /// Time from first touch to separation (s).
    pub contact_time: f64,
    /// Largest normal force (N).
    pub peak_force: f64,
    /// Kinetic energy (translation and rotation) before the impact (J).
    pub kinetic_energy_in: f64,
    /// Kinetic energy (translation and rotation) after the impact (J).
    pub kinetic_energy_out: f64,
    /// Whether the sphere stuck (adhesion): `e_n = 0`, the sphere turned back towards the
    /// target while the contact held (docs/theory.md, "Adhesive impacts").
    pub stuck: bool,
    /// Largest tensile force during the impact (N, ≥ 0; zero without adhesion).
    pub pull_off_force: f64,
    /// Overlap at which the contact let go (m): the residual depth without adhesion, below it
    /// (typically negative) with adhesion; NaN when stuck.
    pub release_overlap: f64,
}

/// Code run with a bound normal law, whichever it is (the laws have different state types).
pub(crate) trait LawVisitor {
    type Output;
    fn visit<L: NormalLaw>(self, law: &L) -> Result<Self::Output>;
}

impl Impact {
    /// A head-on impact of `pair` at speed `speed` (m/s) with the normal law `normal`, closed
    /// form, [`DEFAULT_STEPS_PER_CONTACT`] steps per contact.
    pub fn new(pair: ContactPair, normal: NormalSpec, speed: f64) -> Self {
        Self {
            pair,
            normal,
            method: Method::Closed,
            route: Route::Auto,
            speed,
            angle_degrees: 0.0,
            spin: 0.0,
            friction: 0.0,
            tangential: TangentialSpec::Mindlin,
            steps_per_contact: DEFAULT_STEPS_PER_CONTACT,
            work_of_adhesion: 0.0,
        }
    }

    /// Work of adhesion `Δγ` (J/m², finite, ≥ 0; default 0): Heß's adhesion rule on the MDR
    /// springs ([`AdhesiveMdr`]). Only with the MDR law.
    pub fn work_of_adhesion(mut self, work_of_adhesion: f64) -> Self {
        self.work_of_adhesion = work_of_adhesion;
        self
    }

    /// `Δγ` (J/m²).
    pub fn adhesion(&self) -> f64 {
        self.work_of_adhesion
    }

    /// The paper's Fig. 2 setup (docs/theory.md §7) at speed `speed` (m/s).
    pub fn paper(speed: f64) -> Self {
        Self::new(ContactPair::paper_fig2(), NormalSpec::paper(), speed)
    }

    /// Replace the impact speed (m/s).
    pub fn speed(mut self, speed: f64) -> Self {
        self.speed = speed;
        self
    }

    /// How the normal law is represented (closed form or spring bed).
    pub fn method(mut self, method: Method) -> Self {
        self.method = method;
        self
    }

    /// Energy route or time integration.
    pub fn route(mut self, route: Route) -> Self {
        self.route = route;
        self
    }

    /// Impact angle from the normal, degrees in `[0, 90)`.
    pub fn angle_degrees(mut self, angle: f64) -> Self {
        self.angle_degrees = angle;
        self
    }

    /// Initial angular velocity (rad/s), positive in the sense of rolling forward.
    pub fn spin(mut self, spin: f64) -> Self {
        self.spin = spin;
        self
    }

    /// Friction coefficient `μ` for oblique impacts.
    pub fn friction(mut self, friction: f64) -> Self {
        self.friction = friction;
        self
    }

    /// Tangential law for oblique impacts.
    pub fn tangential(mut self, tangential: TangentialSpec) -> Self {
        self.tangential = tangential;
        self
    }

    /// Time steps per Hertz contact time (≥ 10).
    pub fn steps_per_contact(mut self, steps: usize) -> Self {
        self.steps_per_contact = steps;
        self
    }

    /// The pair.
    pub fn pair(&self) -> &ContactPair {
        &self.pair
    }

    /// The normal law.
    pub fn normal_spec(&self) -> &NormalSpec {
        &self.normal
    }

    /// The impact speed (m/s).
    pub fn impact_speed(&self) -> f64 {
        self.speed
    }

    /// Normal component of the impact velocity (m/s).
    pub fn normal_speed(&self) -> f64 {
        self.speed * self.angle_degrees.to_radians().cos()
    }

    /// Time step (s): the Hertz contact time at the normal speed over the steps per contact.
    pub fn time_step(&self) -> f64 {
        self.pair.hertz_contact_time(self.normal_speed()) / self.steps_per_contact as f64
    }

    fn is_adhesive(&self) -> bool {
        self.work_of_adhesion > 0.0
    }

    fn is_head_on(&self) -> bool {
        self.angle_degrees == 0.0 && self.spin == 0.0
    }

    /// Check every number against its allowed range; errors name the configuration key.
    pub fn validate(&self) -> Result<()> {
        if !(self.speed.is_finite() && self.speed > 0.0) {
            return Err(ImpactError::invalid("speed", self.speed, "a speed > 0 m/s"));
        }
        if !(self.angle_degrees.is_finite() && (0.0..90.0).contains(&self.angle_degrees)) {
            return Err(ImpactError::invalid(
                "angles",
                self.angle_degrees,
                "angles from the normal in [0, 90) degrees",
            ));
        }
        if !self.spin.is_finite() {
            return Err(ImpactError::invalid("spin", self.spin, "a finite number"));
        }
        if !(self.friction.is_finite() && self.friction >= 0.0) {
            return Err(ImpactError::invalid("mu", self.friction, "μ ≥ 0"));
        }
        if self.steps_per_contact < 10 {
            return Err(ImpactError::invalid(
                "steps",
                self.steps_per_contact,
                "at least 10 steps per contact",
            ));
        }
        if !(self.work_of_adhesion.is_finite() && self.work_of_adhesion >= 0.0) {
            return Err(ImpactError::invalid(
                "work-of-adhesion",
                self.work_of_adhesion,
                "a work of adhesion ≥ 0 J/m² (finite)",
            ));
        }
        if self.is_adhesive() {
            if !matches!(self.normal, NormalSpec::Mdr(_)) {
                return Err(ImpactError::invalid(
                    "work-of-adhesion",
                    self.work_of_adhesion,
                    "adhesion is part of the MDR law: use it with --law mdr",
                ));
            }
            if self.tangential == TangentialSpec::SpringBed && !self.is_head_on() {
                return Err(ImpactError::invalid(
                    "tangential",
                    "springs",
                    "the spring-bed tangential law has no adhesion; use the mindlin tangential \
                     law with a work of adhesion",
                ));
            }
            if self.route == Route::Energy {
                return Err(ImpactError::invalid(
                    "route",
                    "energy",
                    "the energy route has no adhesion: integrate in time",
                ));
            }
        }
        if let Method::Springs { springs } = self.method {
            if !matches!(self.normal, NormalSpec::Mdr(_)) {
                return Err(ImpactError::invalid(
                    "method",
                    "springs",
                    "the spring bed is the MDR law: use it with --law mdr",
                ));
            }
            if !(2..=mdr_contact::normal::SpringBed::MAX_SPRINGS).contains(&springs) {
                return Err(ImpactError::invalid("springs", springs, "2 to 1e8 springs"));
            }
        }
        if self.tangential == TangentialSpec::SpringBed
            && !self.is_head_on()
            && !matches!(
                (self.normal, self.method),
                (NormalSpec::Mdr(_), Method::Springs { .. })
            )
        {
            return Err(ImpactError::invalid(
                "tangential",
                "springs",
                "the spring-bed tangential law needs the MDR spring bed (method springs); \
                 use the mindlin tangential law with other normal laws",
            ));
        }
        if self.route == Route::Energy
            && (!matches!(self.normal, NormalSpec::Mdr(_))
                || self.method != Method::Closed
                || !self.is_head_on())
        {
            return Err(ImpactError::invalid(
                "route",
                "energy",
                "the energy route needs the closed-form MDR law and a head-on impact",
            ));
        }
        Ok(())
    }

    /// Bind the normal law to the pair and hand it to `visitor`.
    pub(crate) fn visit_law<V: LawVisitor>(&self, visitor: V) -> Result<V::Output> {
        match (self.normal, self.method) {
            (NormalSpec::Mdr(model), Method::Closed) if self.is_adhesive() => visitor.visit(
                &self
                    .adhesive_model(&model)?
                    .bind(&self.pair)
                    .map_err(ImpactError::parameter("theta-ratio"))?,
            ),
            (NormalSpec::Mdr(model), Method::Springs { springs }) if self.is_adhesive() => {
                let bed = self.spring_bed(&model, springs)?;
                visitor.visit(
                    &AdhesiveSpringBed::new(bed, self.work_of_adhesion)
                        .map_err(ImpactError::parameter("work-of-adhesion"))?
                        .with_sphere_pull_off(&self.pair),
                )
            }
            (NormalSpec::Mdr(model), Method::Closed) => visitor.visit(
                &model
                    .bind(&self.pair)
                    .map_err(ImpactError::parameter("theta-ratio"))?,
            ),
            (NormalSpec::Mdr(model), Method::Springs { springs }) => {
                visitor.visit(&self.spring_bed(&model, springs)?)
            }
            (NormalSpec::Thornton(model), _) => visitor.visit(
                &model
                    .bind(&self.pair)
                    .map_err(ImpactError::parameter("yield-stress"))?,
            ),
            (NormalSpec::Hertz, _) => visitor.visit(
                &Hertz
                    .bind(&self.pair)
                    .map_err(ImpactError::parameter("law"))?,
            ),
            (NormalSpec::Declared(_), _) => {
                unreachable!("a declared law runs through its own compiled entry")
            }
        }
    }

    fn adhesive_model(&self, model: &MdrElastoPlastic) -> Result<AdhesiveMdr> {
        AdhesiveMdr::new(*model, self.work_of_adhesion)
            .map_err(ImpactError::parameter("work-of-adhesion"))
    }

    /// The discrete bed of `springs` springs for this impact. Its half-width is
    /// [`BED_HALF_WIDTH_MARGIN`] times the largest contact radius `sqrt(R d_max)` that the closed
    /// form predicts, so the springs are as fine as the impact allows.
    pub fn spring_bed(&self, model: &MdrElastoPlastic, springs: usize) -> Result<SpringBed> {
        let closed = model
            .bind(&self.pair)
            .map_err(ImpactError::parameter("theta-ratio"))?;
        let d_max = closed
            .impact(
                &MdrState::default(),
                self.pair.reduced_mass(),
                self.normal_speed(),
            )
            .map_err(ImpactError::parameter("speed"))?
            .max_overlap;
        let radius = self.pair.effective_radius();
        SpringBed::sphere(&self.pair, model, springs)
            .map_err(ImpactError::parameter("springs"))?
            .half_width(BED_HALF_WIDTH_MARGIN * (radius * d_max).sqrt())
            .map_err(ImpactError::parameter("springs"))
    }

    /// Speed (m/s) below which this impact is elastic (`e_n = 1`); infinite for Hertz.
    pub fn yield_speed(&self) -> Result<f64> {
        let mass = self.pair.reduced_mass();
        Ok(match self.normal {
            NormalSpec::Mdr(model) => model
                .bind(&self.pair)
                .map_err(ImpactError::parameter("theta-ratio"))?
                .yield_speed(mass),
            NormalSpec::Thornton(model) => model
                .bind(&self.pair)
                .map_err(ImpactError::parameter("yield-stress"))?
                .yield_speed(mass),
            NormalSpec::Hertz => f64::INFINITY,
            NormalSpec::Declared(law) => law.yield_speed(&self.pair)?,
        })
    }

    /// Run the impact.
    pub fn run(&self) -> Result<ImpactOutcome> {
        self.validate()?;
        let use_energy = match self.route {
            Route::Energy => true,
            Route::TimeIntegration => false,
            Route::Auto => {
                matches!(self.normal, NormalSpec::Mdr(_))
                    && self.method == Method::Closed
                    && self.is_head_on()
                    && !self.is_adhesive()
            }
        };
        if use_energy {
            let NormalSpec::Mdr(model) = self.normal else {
                unreachable!("validated above")
            };
            let law = model
                .bind(&self.pair)
                .map_err(ImpactError::parameter("theta-ratio"))?;
            let run = energy_route(&law, self.pair.reduced_mass(), self.speed)
                .map_err(ImpactError::parameter("speed"))?;
            return Ok(self.head_on_outcome(NormalRun {
                restitution: run.restitution,
                max_overlap: run.max_overlap,
                residual_overlap: run.residual_overlap,
                contact_time: run.contact_time,
                peak_force: run.peak_force,
                pull_off_force: 0.0,
                release_overlap: run.residual_overlap,
                stuck: false,
            }));
        }
        if let NormalSpec::Declared(law) = self.normal {
            return if self.is_head_on() {
                Ok(self.head_on_outcome(law.head_on(self, None)?))
            } else {
                law.oblique(self)
            };
        }
        if self.is_head_on() {
            let run = self.visit_law(NormalVisitor {
                impact: self,
                trace: None,
            })?;
            return Ok(self.head_on_outcome(run));
        }
        match (self.tangential, self.normal, self.method) {
            (TangentialSpec::Mindlin, _, _) => self.visit_law(ObliqueVisitor { impact: self }),
            (TangentialSpec::SpringBed, NormalSpec::Mdr(model), Method::Springs { springs }) => {
                let bed = self.spring_bed(&model, springs)?;
                let tangential = SpringBedTangential::new(&self.pair, self.friction)
                    .map_err(ImpactError::parameter("mu"))?;
                let (v_n, v_t) = self.velocity_components();
                let run = integrate_oblique(
                    &bed,
                    &tangential,
                    self.pair.reduced_mass(),
                    self.pair.effective_radius(),
                    v_n,
                    v_t,
                    self.spin,
                    self.time_step(),
                    self.max_steps(),
                )?;
                Ok(self.oblique_outcome(run))
            }
            (TangentialSpec::SpringBed, _, _) => {
                unreachable!("validated: spring bed needs springs")
            }
        }
    }

    fn velocity_components(&self) -> (f64, f64) {
        let angle = self.angle_degrees.to_radians();
        (self.speed * angle.cos(), self.speed * angle.sin())
    }

    fn oblique_outcome(&self, run: ObliqueRun) -> ImpactOutcome {
        let mass = self.pair.reduced_mass();
        let radius = self.pair.effective_radius();
        let (v_n, v_t) = self.velocity_components();
        let inertia = 0.4 * mass * radius * radius;
        let v_n_out = run.normal.restitution * v_n;
        let kinetic =
            |vn: f64, vt: f64, w: f64| 0.5 * mass * (vn * vn + vt * vt) + 0.5 * inertia * w * w;
        ImpactOutcome {
            speed: self.speed,
            angle_degrees: self.angle_degrees,
            normal_restitution: run.normal.restitution,
            tangential_restitution: (v_t > 0.0).then(|| run.tangential_velocity.abs() / v_t),
            tangential_velocity: run.tangential_velocity,
            rebound_angle_degrees: run.tangential_velocity.abs().atan2(v_n_out).to_degrees(),
            spin: run.spin,
            max_overlap: run.normal.max_overlap,
            residual_overlap: run.normal.residual_overlap,
            contact_time: run.normal.contact_time,
            peak_force: run.normal.peak_force,
            kinetic_energy_in: kinetic(v_n, v_t, self.spin),
            kinetic_energy_out: kinetic(v_n_out, run.tangential_velocity, run.spin),
            stuck: run.normal.stuck,
            pull_off_force: run.normal.pull_off_force,
            release_overlap: run.normal.release_overlap,
        }
    }

    /// Integrate a head-on impact in time and return its history (one point per step).
    pub fn trace(&self) -> Result<(ImpactOutcome, Vec<TracePoint>)> {
        self.validate()?;
        if !self.is_head_on() {
            return Err(ImpactError::invalid(
                "angles",
                self.angle_degrees,
                "a trace is recorded for head-on impacts (angle 0, no spin)",
            ));
        }
        let mut points = Vec::with_capacity(self.steps_per_contact + 2);
        let run = match self.normal {
            NormalSpec::Declared(law) => law.head_on(self, Some(&mut points))?,
            _ => self.visit_law(NormalVisitor {
                impact: self,
                trace: Some(&mut points),
            })?,
        };
        Ok((self.head_on_outcome(run), points))
    }

    fn max_steps(&self) -> usize {
        self.steps_per_contact.saturating_mul(200)
    }

    pub(crate) fn head_on_outcome(&self, run: NormalRun) -> ImpactOutcome {
        let mass = self.pair.reduced_mass();
        let v_out = run.restitution * self.speed;
        ImpactOutcome {
            speed: self.speed,
            angle_degrees: 0.0,
            normal_restitution: run.restitution,
            tangential_restitution: None,
            tangential_velocity: 0.0,
            rebound_angle_degrees: 0.0,
            spin: 0.0,
            max_overlap: run.max_overlap,
            residual_overlap: run.residual_overlap,
            contact_time: run.contact_time,
            peak_force: run.peak_force,
            kinetic_energy_in: 0.5 * mass * self.speed * self.speed,
            kinetic_energy_out: 0.5 * mass * v_out * v_out,
            stuck: run.stuck,
            pull_off_force: run.pull_off_force,
            release_overlap: run.release_overlap,
        }
    }
}

pub(crate) struct NormalVisitor<'a> {
    pub(crate) impact: &'a Impact,
    pub(crate) trace: Option<&'a mut Vec<TracePoint>>,
}

impl LawVisitor for NormalVisitor<'_> {
    type Output = NormalRun;
    fn visit<L: NormalLaw>(self, law: &L) -> Result<NormalRun> {
        let i = self.impact;
        integrate_normal(
            law,
            i.pair.reduced_mass(),
            i.speed,
            i.time_step(),
            i.max_steps(),
            self.trace,
        )
    }
}

pub(crate) struct ObliqueVisitor<'a> {
    pub(crate) impact: &'a Impact,
}

impl LawVisitor for ObliqueVisitor<'_> {
    type Output = ImpactOutcome;
    fn visit<L: NormalLaw>(self, law: &L) -> Result<ImpactOutcome> {
        let i = self.impact;
        let tangential = Mindlin::new(i.friction)
            .map_err(ImpactError::parameter("mu"))?
            .bind(&i.pair)
            .map_err(ImpactError::parameter("mu"))?;
        let (v_n, v_t) = i.velocity_components();
        let run = integrate_oblique(
            law,
            &tangential,
            i.pair.reduced_mass(),
            i.pair.effective_radius(),
            v_n,
            v_t,
            i.spin,
            i.time_step(),
            i.max_steps(),
        )?;
        Ok(i.oblique_outcome(run))
    }
}
