//! The law-parameter flags of the validator, derived from the declarations of the registered
//! normal laws (`mdr_sim::laws::registry::NORMAL_LAWS`): one flag per declared parameter
//! (`--qc`, `--theta-ratio`, `--yield-stress`, `--normal-stiffness-n-per-m`, …), named, helped
//! and range-checked as its law declares it. The same names are the `--config` file's keys. A
//! law added to the registry brings its flags with it.

use anyhow::anyhow;
use clap::{Arg, ArgMatches, Args, Command, FromArgMatches};
use mdr_contact::params::{LawDeclaration, Param, ParamProblem};
use mdr_sim::laws::registry::NORMAL_LAWS;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::sync::OnceLock;

/// The value of each given law-parameter flag, by flag name (without `--`).
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
#[serde(transparent)]
pub struct LawParamArgs {
    values: BTreeMap<String, f64>,
}

/// One flag: its name and the parameter it sets (the first law's declaration of that name).
struct LawFlag {
    name: &'static str,
    value_name: &'static str,
    param: &'static Param,
    laws: Vec<&'static str>,
}

/// Every registered law's parameters as flags, each flag once, in registry order.
fn law_flags() -> &'static [LawFlag] {
    static FLAGS: OnceLock<Vec<LawFlag>> = OnceLock::new();
    FLAGS.get_or_init(|| {
        let mut flags: Vec<LawFlag> = Vec::new();
        for entry in NORMAL_LAWS {
            let law = entry.declaration.name;
            for param in entry.declaration.params {
                let name = param.flag_name();
                match flags.iter_mut().find(|f| f.name == name) {
                    Some(flag) => flag.laws.push(law),
                    // Leaked once per flag of a registered law: clap's names are 'static.
                    None => flags.push(LawFlag {
                        name: Box::leak(name.into_boxed_str()),
                        value_name: Box::leak(value_name(param.unit).into_boxed_str()),
                        param,
                        laws: vec![law],
                    }),
                }
            }
        }
        flags
    })
}

/// The validator's default of a parameter as its help text says it.
fn default_text(param: &Param) -> String {
    match (mdr_impact::law::validator_default(param), param.key) {
        (Some(value), _) => format!("{value:e}"),
        (None, "yield_pressure_pa") => "the value whose yield speed equals the MDR law's".into(),
        _ => "none, required with its law".into(),
    }
}

fn flag_arg(flag: &LawFlag) -> Arg {
    Arg::new(flag.name)
        .long(flag.name)
        .value_name(flag.value_name)
        .allow_negative_numbers(true)
        .value_parser(clap::value_parser!(f64))
        .help(format!(
            "{} [law: {}] [default: {}]",
            flag.param.help(),
            flag.laws.join(", "),
            default_text(flag.param)
        ))
}

/// The value placeholder of a unit: `N/m` → `N_PER_M`, dimensionless → `VALUE`.
fn value_name(unit: &str) -> String {
    if unit == "1" {
        return "VALUE".into();
    }
    unit.replace('/', "_PER_")
        .chars()
        .filter(|c| c.is_ascii_alphanumeric() || *c == '_')
        .collect::<String>()
        .to_uppercase()
}

impl Args for LawParamArgs {
    fn augment_args(mut cmd: Command) -> Command {
        for flag in law_flags() {
            // A flag the command already has (a validator option of the same name) stays its.
            if cmd.get_arguments().any(|a| a.get_long() == Some(flag.name)) {
                continue;
            }
            cmd = cmd.arg(flag_arg(flag));
        }
        cmd
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}

impl FromArgMatches for LawParamArgs {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        let mut args = Self::default();
        args.update_from_arg_matches(matches)?;
        Ok(args)
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        for flag in law_flags() {
            if let Ok(Some(&value)) = matches.try_get_one::<f64>(flag.name) {
                self.values.insert(flag.name.to_owned(), value);
            }
        }
        Ok(())
    }
}

impl LawParamArgs {
    /// The flags' values over the file's (`--config`), whose keys must be flags.
    pub(super) fn merged(&self, file: &LawParamArgs) -> anyhow::Result<LawParamArgs> {
        if let Some(key) = file
            .values
            .keys()
            .find(|k| !law_flags().iter().any(|f| f.name == *k))
        {
            return Err(anyhow!("unknown key `{key}`"));
        }
        let mut values = file.values.clone();
        values.extend(self.values.iter().map(|(k, v)| (k.clone(), *v)));
        Ok(LawParamArgs { values })
    }

    /// The value given for `param`'s flag, if any.
    pub(crate) fn given(&self, param: &Param) -> Option<f64> {
        self.values.get(&param.flag_name()).copied()
    }

    /// The flags given that set none of `laws`' parameters.
    pub(super) fn unused_by(&self, laws: &[&LawDeclaration]) -> Vec<String> {
        self.values
            .keys()
            .filter(|k| {
                !laws
                    .iter()
                    .flat_map(|l| l.params)
                    .any(|p| p.flag_name() == **k)
            })
            .map(|k| format!("--{k}"))
            .collect()
    }

    /// The values of `law`'s parameters in declared order: the flag's, else the validator's
    /// default ([`mdr_impact::law::validator_default`]), else `fallback`'s; each checked
    /// against its declared range. Errors name the flag, the range and the equation.
    pub(crate) fn values(
        &self,
        law: &LawDeclaration,
        fallback: impl Fn(&Param) -> Option<f64>,
    ) -> anyhow::Result<Vec<f64>> {
        law.values(|p| {
            self.given(p)
                .or_else(|| mdr_impact::law::validator_default(p))
                .or_else(|| fallback(p))
        })
        .map_err(|problems| match &problems[0] {
            ParamProblem::Missing(p) => anyhow!(
                "invalid value for --law: `{}` needs --{} ({})",
                law.name,
                p.flag_name(),
                p.help()
            ),
            problem @ ParamProblem::Invalid(p, _) => {
                anyhow!("invalid value for --{}: {problem}", p.flag_name())
            }
        })
    }
}

/// The registered law named `name` (`-` read as `_`), or the error naming `--law` and the
/// registered names.
pub(crate) fn registered_law(
    name: &str,
) -> anyhow::Result<&'static mdr_sim::laws::registry::NormalEntry> {
    let canonical = name.replace('-', "_");
    mdr_sim::laws::registry::normal_law(&canonical).ok_or_else(|| {
        anyhow!(
            "invalid value for --law: `{name}` (registered: {})",
            mdr_sim::laws::registry::normal_law_names().join(", ")
        )
    })
}
