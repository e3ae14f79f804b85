//! `pair_coeff` keywords of `pair_style mdrdem`: parsing with range checks that name the keyword,
//! and the per-type-pair models (materials mixed as mdr-contact mixes them: `E*` eq. 3, `G*`
//! docs/theory.md §5; the work of adhesion by the geometric mean, [`mixed_work_of_adhesion`]).

use crate::error::PluginError;
use crate::keywords;
use mdr_contact::damping::HertzianViscous;
use mdr_contact::material::{effective_modulus, effective_shear_modulus, Material};
use mdr_contact::model::ContactModel;
use mdr_contact::normal::{AdhesiveMdr, MdrElastoPlastic};
use mdr_contact::rolling::EpsdRolling;
use mdr_contact::tangential::Mindlin;

/// The composed model every pair of the plugin uses: MDR normal law, Mindlin tangential law,
/// Hertzian viscous damping (with its tangential dashpot).
pub type PluginModel = ContactModel<MdrElastoPlastic, Mindlin, HertzianViscous>;

/// One `pair_coeff` line, checked: every keyword with its value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoeffLine {
    /// `youngs`: Young's modulus `E` (pressure units, > 0).
    pub youngs: f64,
    /// `poisson`: Poisson's ratio `ν` in (−1, 0.5].
    pub poisson: f64,
    /// `qc`: critical line load `q_c` (force/length, ≥ 0), eq. (7).
    pub qc: f64,
    /// `theta`: hardening ratio `Θ/E*` in [0, 1], eq. (12).
    pub theta: f64,
    /// `friction`: Coulomb coefficient `μ` (≥ 0; default 0).
    pub friction: f64,
    /// `damping`: `γ_n` of the Hertzian viscous damping (1/(time·length^{1/2}), ≥ 0; default 0).
    pub damping: f64,
    /// `tangential_damping`: ratio of the tangential to the normal dashpot (≥ 0; default 0).
    pub tangential_damping: f64,
    /// `rolling`: EPSD rolling-resistance coefficient `μ_r` (≥ 0; default 0 = none).
    pub rolling: f64,
    /// `adhesion`: work of adhesion `Δγ` of Heß's rule (energy/area, J/m² in SI, ≥ 0; default
    /// 0 = none), docs/theory.md §9.
    pub adhesion: f64,
    /// `estar`: `E*` of the pair given directly (pressure, > 0), instead of eq. (3).
    pub estar: Option<f64>,
    /// `gstar`: `G*` of the pair given directly (pressure, > 0), instead of docs/theory.md §5.
    pub gstar: Option<f64>,
}

impl CoeffLine {
    /// Parse the keyword-value words after `pair_coeff I J` ([`crate::keywords::KEYWORDS`]).
    pub fn parse<S: AsRef<str>>(words: &[S]) -> Result<Self, PluginError> {
        let values = keywords::parse(words)?;
        let get = |k: &'static str| keywords::value(&values, k);
        let required = |k: &'static str| get(k).map(|v| v.unwrap_or_default());
        let line = CoeffLine {
            youngs: required("youngs")?,
            poisson: required("poisson")?,
            qc: required("qc")?,
            theta: required("theta")?,
            friction: required("friction")?,
            damping: required("damping")?,
            tangential_damping: required("tangential_damping")?,
            rolling: required("rolling")?,
            adhesion: required("adhesion")?,
            estar: get("estar")?,
            gstar: get("gstar")?,
        };
        line.check()?;
        Ok(line)
    }

    /// Range checks, each naming its keyword; then the mdr-contact constructors (which check
    /// the same ranges again) so that nothing reaches the law that the law would refuse.
    fn check(&self) -> Result<(), PluginError> {
        let given = [
            ("youngs", Some(self.youngs)),
            ("poisson", Some(self.poisson)),
            ("qc", Some(self.qc)),
            ("theta", Some(self.theta)),
            ("friction", Some(self.friction)),
            ("damping", Some(self.damping)),
            ("tangential_damping", Some(self.tangential_damping)),
            ("rolling", Some(self.rolling)),
            ("adhesion", Some(self.adhesion)),
            ("estar", self.estar),
            ("gstar", self.gstar),
        ];
        for (keyword, value) in given {
            if let Some(v) = value {
                keywords::checked(keyword, v)?;
            }
        }
        self.material()?;
        self.model()?;
        self.rolling_model()?;
        AdhesiveMdr::new(MdrElastoPlastic::elastic(), self.adhesion)
            .map_err(|e| PluginError::law("adhesion", e))?;
        Ok(())
    }

    /// The material of this line (density unused: masses come from LAMMPS).
    pub fn material(&self) -> Result<Material, PluginError> {
        Material::new(self.youngs, self.poisson, 1.0).map_err(|e| PluginError::law("youngs", e))
    }

    /// The contact model of this line.
    pub fn model(&self) -> Result<PluginModel, PluginError> {
        let normal =
            MdrElastoPlastic::new(self.qc, self.theta).map_err(|e| PluginError::law("qc", e))?;
        let tangential =
            Mindlin::new(self.friction).map_err(|e| PluginError::law("friction", e))?;
        let damping = HertzianViscous::new(self.damping)
            .and_then(|d| d.with_tangential_ratio(self.tangential_damping))
            .map_err(|e| PluginError::law("damping", e))?;
        Ok(ContactModel::new(normal)
            .with_tangential(tangential)
            .with_damping(damping))
    }

    /// The rolling model of this line.
    pub fn rolling_model(&self) -> Result<EpsdRolling, PluginError> {
        EpsdRolling::new(self.rolling).map_err(|e| PluginError::law("rolling", e))
    }

    /// The law parameters that must agree between two types to mix them (everything except the
    /// material and the work of adhesion, which are mixed).
    fn law_parameters(&self) -> [(&'static str, f64); 6] {
        [
            ("qc", self.qc),
            ("theta", self.theta),
            ("friction", self.friction),
            ("damping", self.damping),
            ("tangential_damping", self.tangential_damping),
            ("rolling", self.rolling),
        ]
    }
}

/// The work of adhesion between two materials from their own, `Δγ_ij = √(Δγ_ii Δγ_jj)`: the
/// geometric-mean combining rule of surface energies (Girifalco & Good, J. Phys. Chem. 61, 904,
/// 1957, with their interaction parameter 1), the rule LAMMPS's `pair granular` applies to the
/// cohesion of its `jkr` and `dmt` models (`mix_geom` in `GranSubModNormalJKR::mix_coeffs`).
pub fn mixed_work_of_adhesion(a: f64, b: f64) -> f64 {
    (a * b).sqrt()
}

/// What every contact between two given atom types uses: the model and the pair moduli.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairModel {
    /// Normal + tangential + damping sub-models (the normal law without adhesion).
    pub model: PluginModel,
    /// Rolling resistance (a coefficient of 0 gives no torque).
    pub rolling: EpsdRolling,
    /// Work of adhesion `Δγ` of the pair (energy/area; 0: no adhesion): Heß's rule on the MDR
    /// springs (`mdr_contact::normal::AdhesiveMdrLaw`).
    pub adhesion: f64,
    /// `E*` of the pair (pressure).
    pub effective_modulus: f64,
    /// `G*` of the pair (pressure).
    pub effective_shear_modulus: f64,
}

impl PairModel {
    /// The pair model of an explicit `pair_coeff I J` line: both bodies of the line's material.
    pub fn explicit(line: &CoeffLine) -> Result<Self, PluginError> {
        let m = line.material()?;
        Ok(Self {
            model: line.model()?,
            rolling: line.rolling_model()?,
            adhesion: line.adhesion,
            effective_modulus: line.estar.unwrap_or_else(|| effective_modulus(&m, &m)),
            effective_shear_modulus: line
                .gstar
                .unwrap_or_else(|| effective_shear_modulus(&m, &m)),
        })
    }

    /// Mix the lines of types I (`pair_coeff I I`) and J (`pair_coeff J J`): `E*` by eq. (3),
    /// `G*` by docs/theory.md §5 from the two materials, the work of adhesion by
    /// [`mixed_work_of_adhesion`]; the other law parameters must agree (mdr-dem uses one model for
    /// every pair of a simulation and mixes only materials).
    pub fn mixed(i: usize, a: &CoeffLine, j: usize, b: &CoeffLine) -> Result<Self, PluginError> {
        for ((keyword, va), (_, vb)) in a.law_parameters().iter().zip(b.law_parameters()) {
            if *va != vb {
                return Err(PluginError::CannotMix {
                    i,
                    j,
                    keyword: keyword.to_string(),
                });
            }
        }
        let (ma, mb) = (a.material()?, b.material()?);
        Ok(Self {
            model: a.model()?,
            rolling: a.rolling_model()?,
            adhesion: mixed_work_of_adhesion(a.adhesion, b.adhesion),
            effective_modulus: effective_modulus(&ma, &mb),
            effective_shear_modulus: effective_shear_modulus(&ma, &mb),
        })
    }

    /// Whether this pair has rolling resistance.
    pub fn has_rolling(&self) -> bool {
        self.rolling.coefficient() > 0.0
    }

    /// Whether this pair's contacts are adhesive.
    pub fn has_adhesion(&self) -> bool {
        self.adhesion > 0.0
    }

    /// The largest separation (length, ≥ 0) at which a contact of this pair with effective radius
    /// `effective_radius` can still hold: the elastic JKR snap-off distance
    /// `(3/4) (π² Δγ² R / E*²)^{1/3}`, a bound over every load history of the adhesive MDR law
    /// (docs/theory.md §9.2, eq. A11). It grows with `R`, so the largest spheres of two types
    /// bound every pair of them. Zero without adhesion.
    pub fn neck_reach(&self, effective_radius: f64) -> f64 {
        if !self.has_adhesion() || effective_radius.is_nan() || effective_radius <= 0.0 {
            return 0.0;
        }
        let ratio = std::f64::consts::PI * self.adhesion / self.effective_modulus;
        0.75 * (ratio * ratio * effective_radius).cbrt()
    }
}

/// The coefficients of all type pairs of one `pair_style mdrdem` (types 1..=ntypes).
#[derive(Debug, Clone, PartialEq)]
pub struct CoeffTable {
    ntypes: usize,
    lines: Vec<Option<CoeffLine>>,
    models: Vec<Option<PairModel>>,
}

impl CoeffTable {
    /// An empty table for `ntypes` atom types.
    pub fn new(ntypes: usize) -> Self {
        let n = (ntypes + 1) * (ntypes + 1);
        Self {
            ntypes,
            lines: vec![None; n],
            models: vec![None; n],
        }
    }

    /// Number of atom types.
    pub fn ntypes(&self) -> usize {
        self.ntypes
    }

    fn index(&self, i: usize, j: usize) -> usize {
        i * (self.ntypes + 1) + j
    }

    /// Apply a `pair_coeff` line to types `ilo..=ihi` × `jlo..=jhi` (only `i ≤ j` is stored, as
    /// LAMMPS does).
    pub fn set(
        &mut self,
        (ilo, ihi): (usize, usize),
        (jlo, jhi): (usize, usize),
        line: CoeffLine,
    ) -> Result<usize, PluginError> {
        let mut count = 0;
        for i in ilo..=ihi {
            for j in jlo.max(i)..=jhi {
                if i < 1 || j > self.ntypes {
                    return Err(PluginError::TypeRange { i, j });
                }
                let k = self.index(i, j);
                self.lines[k] = Some(line);
                count += 1;
            }
        }
        Ok(count)
    }

    /// The explicit line of pair `(i, j)`, if any.
    pub fn line(&self, i: usize, j: usize) -> Option<&CoeffLine> {
        let (i, j) = (i.min(j), i.max(j));
        self.lines[self.index(i, j)].as_ref()
    }

    /// Build the model of pair `(i, j)` (LAMMPS `init_one`): the explicit line, or the mix of
    /// `(i, i)` and `(j, j)`.
    pub fn init_one(&mut self, i: usize, j: usize) -> Result<PairModel, PluginError> {
        let (i, j) = (i.min(j), i.max(j));
        if i < 1 || j > self.ntypes {
            return Err(PluginError::TypeRange { i, j });
        }
        let model = match (self.line(i, j), self.line(i, i), self.line(j, j)) {
            (Some(line), _, _) => PairModel::explicit(line)?,
            (None, Some(a), Some(b)) => PairModel::mixed(i, a, j, b)?,
            _ => return Err(PluginError::NotSet { i, j }),
        };
        for (a, b) in [(i, j), (j, i)] {
            let k = self.index(a, b);
            self.models[k] = Some(model);
        }
        Ok(model)
    }

    /// The model of pair `(i, j)` after [`CoeffTable::init_one`].
    #[inline(always)]
    pub fn model(&self, i: usize, j: usize) -> Option<&PairModel> {
        self.models
            .get(i * (self.ntypes + 1) + j)
            .and_then(|m| m.as_ref())
    }

    /// Whether any initialised pair has rolling resistance.
    pub fn has_rolling(&self) -> bool {
        self.models.iter().flatten().any(PairModel::has_rolling)
    }

    /// Whether any initialised pair is adhesive.
    pub fn has_adhesion(&self) -> bool {
        self.models.iter().flatten().any(PairModel::has_adhesion)
    }
}
