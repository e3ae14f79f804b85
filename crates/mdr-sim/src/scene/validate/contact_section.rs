//! `[contact]`: the normal, tangential, damping and rolling sub-models and their parameters.

use super::*;

impl Checker<'_, '_> {
    pub(super) fn contact(&mut self, c: &ContactSection) -> Option<ContactSpec> {
        let table = KeyPath::root().key("contact");
        let normal = self.normal_law(c, &table);
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
            None => registry::sub_model_default("rolling_friction"),
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
            None => registry::sub_model_default("damping_tangential_ratio"),
        };
        Some(ContactSpec {
            normal: normal?,
            friction: friction?,
            damping: damping?,
            tangential_damping_ratio: tangential_damping?,
            rolling_friction: rolling?,
            works_of_adhesion: Vec::new(),
        })
    }
}

/// The keys of `[contact]` besides the normal law's parameters.
const CONTACT_KEYS: &[&str] = &[
    "normal",
    "tangential",
    "friction",
    "damping",
    "damping_gamma_n_per_m_s",
    "damping_eta",
    "damping_tangential_ratio",
    "rolling_friction",
];

impl Checker<'_, '_> {
    /// `normal = "…"` and its parameters: a registered law's name, each of its declared
    /// parameters given (a scene states all of its physics) and in its declared range, and no
    /// parameter of another law.
    fn normal_law(&mut self, c: &ContactSection, table: &KeyPath) -> Option<NormalSpec> {
        let Some(entry) = registry::normal_law(&c.normal) else {
            let names: Vec<String> = registry::normal_law_names()
                .iter()
                .map(|n| format!("`{n}`"))
                .collect();
            self.error(
                &table.key("normal"),
                with_suggestion(&format!(
                    "unknown variant `{}`, expected one of {}",
                    c.normal,
                    names.join(", ")
                )),
            );
            return None;
        };
        let law = entry.declaration;
        let mut ok = true;
        for (key, value) in &c.law_parameters {
            if law.param(key).is_some() {
                if let ParamValue::Other(v) = value {
                    self.error(
                        &table.key(key),
                        format!("invalid type: {}, expected a number", v.type_str()),
                    );
                    ok = false;
                }
                continue;
            }
            ok = false;
            let declared_by_another = registry::NORMAL_LAWS
                .iter()
                .any(|e| e.declaration.param(key).is_some());
            if declared_by_another {
                self.unused(
                    table,
                    &[(key, true)],
                    &format!("by normal = \"{}\"", law.name),
                );
            } else {
                let expected: Vec<String> = CONTACT_KEYS
                    .iter()
                    .copied()
                    .chain(law.params.iter().map(|p| p.key))
                    .map(|k| format!("`{k}`"))
                    .collect();
                self.error(
                    &table.key(key),
                    with_suggestion(&format!(
                        "unknown field `{key}`, expected one of {}",
                        expected.join(", ")
                    )),
                );
            }
        }
        let values = law.values(|p| match c.law_parameters.get(p.key) {
            Some(ParamValue::Number(v)) => Some(*v),
            // Reported above as not a number.
            Some(ParamValue::Other(_)) => Some(f64::NAN),
            None => None,
        });
        let values = match values {
            Ok(values) => values,
            Err(problems) => {
                for problem in problems {
                    match problem {
                        ParamProblem::Missing(p) => {
                            self.require(
                                table,
                                p.key,
                                None::<f64>,
                                &format!("required by normal = \"{}\": {}", law.name, p.help()),
                            );
                        }
                        ParamProblem::Invalid(p, _)
                            if matches!(
                                c.law_parameters.get(p.key),
                                Some(ParamValue::Other(_))
                            ) => {}
                        ParamProblem::Invalid(p, e) => {
                            self.error(&table.key(p.key), format!("{e}: {}", p.help()));
                        }
                    }
                }
                return None;
            }
        };
        if let Err(e) = entry.check(&values) {
            self.contact_error(table, e);
            return None;
        }
        ok.then_some(NormalSpec {
            law: law.name,
            values,
        })
    }
}
