//! `[contact]`: the normal, tangential, damping and rolling sub-models and their parameters.

use super::*;

impl Checker<'_, '_> {
    pub(super) fn contact(&mut self, c: &ContactSection) -> Option<ContactSpec> {
        let table = KeyPath::root().key("contact");
        let why = |law: &str| format!("by normal = \"{law}\"");
        let normal = match c.normal {
            NormalLawName::Mdr => {
                self.unused(
                    &table,
                    &[("yield_pressure_pa", c.yield_pressure_pa.is_some())],
                    &why("mdr"),
                );
                let q = self.require(
                    &table,
                    "critical_line_load_n_per_m",
                    c.critical_line_load_n_per_m,
                    "required by normal = \"mdr\"",
                );
                let h = self.require(
                    &table,
                    "hardening_ratio",
                    c.hardening_ratio,
                    "required by normal = \"mdr\"",
                );
                match (q, h) {
                    (Some(q), Some(h)) => match MdrElastoPlastic::new(q, h) {
                        Ok(_) => Some(NormalSpec::Mdr {
                            critical_line_load: q,
                            hardening_ratio: h,
                        }),
                        Err(e) => {
                            self.contact_error(&table, e);
                            None
                        }
                    },
                    _ => None,
                }
            }
            NormalLawName::Hertz => {
                self.unused(
                    &table,
                    &[
                        (
                            "critical_line_load_n_per_m",
                            c.critical_line_load_n_per_m.is_some(),
                        ),
                        ("hardening_ratio", c.hardening_ratio.is_some()),
                        ("yield_pressure_pa", c.yield_pressure_pa.is_some()),
                    ],
                    &why("hertz"),
                );
                Some(NormalSpec::Hertz)
            }
            NormalLawName::Thornton => {
                self.unused(
                    &table,
                    &[
                        (
                            "critical_line_load_n_per_m",
                            c.critical_line_load_n_per_m.is_some(),
                        ),
                        ("hardening_ratio", c.hardening_ratio.is_some()),
                    ],
                    &why("thornton"),
                );
                let p = self.require(
                    &table,
                    "yield_pressure_pa",
                    c.yield_pressure_pa,
                    "required by normal = \"thornton\"",
                )?;
                match Thornton::new(p) {
                    Ok(_) => Some(NormalSpec::Thornton { yield_pressure: p }),
                    Err(e) => {
                        self.contact_error(&table, e);
                        None
                    }
                }
            }
        };
        let tangential = c.tangential.unwrap_or(TangentialLawName::None);
        let friction = match (tangential, c.friction) {
            (TangentialLawName::None, Some(mu)) if mu != 0.0 => {
                self.error(
                    &table.key("friction"),
                    "friction needs tangential = \"mindlin\" (tangential is \"none\")",
                );
                None
            }
            (TangentialLawName::Mindlin, None) => {
                self.require(
                    &table,
                    "friction",
                    None::<f64>,
                    "required by tangential = \"mindlin\"",
                );
                None
            }
            (_, mu) => {
                let mu = mu.unwrap_or(0.0);
                match Mindlin::new(mu) {
                    Ok(_) => Some(mu),
                    Err(e) => {
                        self.contact_error(&table, e);
                        None
                    }
                }
            }
        };
        let damping = match c.damping {
            DampingLawName::None => {
                self.unused(
                    &table,
                    &[
                        (
                            "damping_gamma_n_per_m_s",
                            c.damping_gamma_n_per_m_s.is_some(),
                        ),
                        ("damping_eta", c.damping_eta.is_some()),
                        (
                            "damping_tangential_ratio",
                            c.damping_tangential_ratio.is_some(),
                        ),
                    ],
                    "by damping = \"none\"",
                );
                Some(DampingSpec::None)
            }
            DampingLawName::HertzianViscous => {
                self.unused(
                    &table,
                    &[("damping_eta", c.damping_eta.is_some())],
                    "by damping = \"hertzian_viscous\"",
                );
                let g = self.require(
                    &table,
                    "damping_gamma_n_per_m_s",
                    c.damping_gamma_n_per_m_s,
                    "required by damping = \"hertzian_viscous\"",
                )?;
                match HertzianViscous::new(g) {
                    Ok(_) => Some(DampingSpec::HertzianViscous(g)),
                    Err(e) => {
                        self.contact_error(&table, e);
                        None
                    }
                }
            }
            DampingLawName::StiffnessViscous => {
                self.unused(
                    &table,
                    &[(
                        "damping_gamma_n_per_m_s",
                        c.damping_gamma_n_per_m_s.is_some(),
                    )],
                    "by damping = \"stiffness_viscous\"",
                );
                let eta = self.require(
                    &table,
                    "damping_eta",
                    c.damping_eta,
                    "required by damping = \"stiffness_viscous\"",
                )?;
                match StiffnessViscous::new(eta) {
                    Ok(_) => Some(DampingSpec::StiffnessViscous(eta)),
                    Err(e) => {
                        self.contact_error(&table, e);
                        None
                    }
                }
            }
        };
        let rolling = match c.rolling_friction {
            Some(mu_r) => match EpsdRolling::new(mu_r) {
                Ok(_) => Some(mu_r),
                Err(e) => {
                    self.contact_error(&table, e);
                    None
                }
            },
            None => Some(0.0),
        };
        let tangential_damping = match c.damping_tangential_ratio {
            Some(ratio) => {
                match HertzianViscous::new(0.0).and_then(|d| d.with_tangential_ratio(ratio)) {
                    Ok(_) => Some(ratio),
                    Err(e) => {
                        self.contact_error(&table, e);
                        None
                    }
                }
            }
            None => Some(0.0),
        };
        Some(ContactSpec {
            normal: normal?,
            friction: friction?,
            damping: damping?,
            tangential_damping_ratio: tangential_damping?,
            rolling_friction: rolling?,
        })
    }
}
