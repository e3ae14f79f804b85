//! `[contact]`: the normal, tangential, damping and rolling laws, each by its registered name,
//! and their parameters, each read, defaulted and range-checked as its law declares it.

use super::*;
use crate::laws::registry::{SubModelKind, SUB_MODEL_KINDS};
use crate::scene::SubModelSpec;
use mdr_contact::params::LawDeclaration;

impl Checker<'_, '_> {
    pub(super) fn contact(&mut self, c: &ContactSection) -> Option<ContactSpec> {
        let table = KeyPath::root().key("contact");
        let normal = self.normal_law(c, &table);
        let [tangential, damping, rolling] = SUB_MODEL_KINDS
            .each_ref()
            .map(|kind| self.sub_model(c, &table, kind));
        Some(registry::contact_spec(
            normal?,
            tangential?,
            damping?,
            rolling?,
        ))
    }

    /// The law of one sub-model kind (`tangential = "…"`, its default when absent) and its
    /// declared parameters: each given or defaulted, and in its declared range; a parameter
    /// only the kind's other laws declare is refused unless it is 0 (the coefficient of a law
    /// that is off).
    fn sub_model(
        &mut self,
        c: &ContactSection,
        table: &KeyPath,
        kind: &SubModelKind,
    ) -> Option<SubModelSpec> {
        let name = c.chosen(kind.kind).unwrap_or(kind.default);
        let Some(entry) = kind.law(name) else {
            let names: Vec<String> = kind.names().iter().map(|n| format!("`{n}`")).collect();
            self.error(
                &table.key(kind.key),
                with_suggestion(&format!(
                    "unknown variant `{name}`, expected one of {}",
                    names.join(", ")
                )),
            );
            return None;
        };
        let law = entry.declaration;
        let mut ok = true;
        for key in kind.keys() {
            if law.param(key).is_some() {
                continue;
            }
            match c.law_parameters.get(key) {
                None | Some(ParamValue::Number(0.0)) => {}
                Some(_) => {
                    ok = false;
                    let owners: Vec<String> = kind
                        .declaring(key)
                        .iter()
                        .map(|n| format!("`{n}`"))
                        .collect();
                    self.error(
                        &table.key(key),
                        format!(
                            "this key is not used by {} = \"{name}\" (a parameter of {}): remove it",
                            kind.key,
                            owners.join(", ")
                        ),
                    );
                }
            }
        }
        let values = self.declared_values(c, table, &law, kind.key)?;
        if let Err(e) = entry.check(&values) {
            self.contact_error(table, e);
            return None;
        }
        ok.then_some(SubModelSpec {
            declaration: law,
            values,
        })
    }

    /// The values of `law`'s parameters from the table, in declared order: each given as a
    /// number or defaulted, and in its declared range; every problem reported at its key.
    /// `chosen_by`: the key naming the law (`normal`, `tangential`, …).
    fn declared_values(
        &mut self,
        c: &ContactSection,
        table: &KeyPath,
        law: &LawDeclaration,
        chosen_by: &str,
    ) -> Option<Vec<f64>> {
        for p in law.params {
            if let Some(ParamValue::Other(v)) = c.law_parameters.get(p.key) {
                self.error(
                    &table.key(p.key),
                    format!("invalid type: {}, expected a number", v.type_str()),
                );
            }
        }
        let values = law.values(|p| match c.law_parameters.get(p.key) {
            Some(ParamValue::Number(v)) => Some(*v),
            // Reported above as not a number.
            Some(ParamValue::Other(_)) => Some(f64::NAN),
            None => None,
        });
        match values {
            Ok(values) => Some(values),
            Err(problems) => {
                for problem in problems {
                    match problem {
                        ParamProblem::Missing(p) => {
                            self.require(
                                table,
                                p.key,
                                None::<f64>,
                                &format!(
                                    "required by {chosen_by} = \"{}\": {}",
                                    law.name,
                                    p.help()
                                ),
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
                None
            }
        }
    }

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
        for key in c.law_parameters.keys() {
            if law.param(key).is_some() || registry::is_sub_model_key(key) {
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
                let expected: Vec<String> = contact_keys()
                    .into_iter()
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
        let values = self.declared_values(c, table, &law, "normal")?;
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

/// The keys of `[contact]` besides the normal law's parameters: `normal`, then each sub-model
/// kind's key and its laws' parameters.
fn contact_keys() -> Vec<&'static str> {
    let mut keys = vec!["normal"];
    for kind in &SUB_MODEL_KINDS {
        keys.push(kind.key);
        keys.extend(kind.keys());
    }
    keys
}
