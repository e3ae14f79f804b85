//! The macros that turn the registry's list of tangential, damping or rolling laws
//! ([`super::registry`]) into what the scenes' steppers run: for each kind, the registry's
//! entries ([`super::registry::SubModelEntry`]), an enum of the registered models with a variant
//! per law (`AnyTangential`, `AnyDamping`, `AnyRolling`), the enum of their laws bound to a pair,
//! the kind's model and law traits implemented by a `match` forwarding to the law's own
//! implementation, and the model made from a scene's validated choice
//! ([`crate::scene::SubModelSpec`]) by the law's [`mdr_contact::params::Declared::from_values`].
//!
//! A contact dispatches on the variant with a `match`: no call through a pointer, and a branch
//! the processor predicts (every contact of a scene takes the same one). The normal law alone
//! is compiled into the steppers (docs/architecture.md, "Tangential, damping and rolling
//! laws").
//!
//! The per-contact history of a tangential or rolling law lives in its kind's history type (the
//! type a checkpoint records: Mindlin's and the elastic–plastic rolling spring's); a law whose
//! history is that type or none ([`HistoryIn`]) needs nothing more.

use mdr_contact::rolling::EpsdRollingState;
use mdr_contact::tangential::MindlinState;

/// A sub-model's per-contact history held in its kind's history type `H`: the same type, or
/// none (`()`: the law keeps no history, and `H` stays default).
pub trait HistoryIn<H> {
    /// Run `f` on the history held in `history`.
    fn update_in<T>(history: &mut H, f: impl FnOnce(&mut Self) -> T) -> T;
    /// The history held in `history`.
    fn read_in(history: &H) -> &Self;
}

macro_rules! history_in_itself_or_none {
    ($($history:ty),*) => {$(
        impl HistoryIn<$history> for $history {
            #[inline(always)]
            fn update_in<T>(history: &mut $history, f: impl FnOnce(&mut Self) -> T) -> T {
                f(history)
            }
            #[inline(always)]
            fn read_in(history: &$history) -> &Self {
                history
            }
        }

        impl HistoryIn<$history> for () {
            #[inline(always)]
            fn update_in<T>(_: &mut $history, f: impl FnOnce(&mut ()) -> T) -> T {
                f(&mut ())
            }
            #[inline(always)]
            fn read_in(_: &$history) -> &() {
                &()
            }
        }
    )*};
}

history_in_itself_or_none!(MindlinState, EpsdRollingState);

/// The part every kind shares: the registry's entries, the model and law enums, the model made
/// from a validated choice, the model trait's `bind`.
macro_rules! sub_model_enums {
    (
        $kind:literal, $list:ident, $model:ident, $law:ident, $Model:ident,
        [$( $(#[$attr:meta])* $variant:ident: $ty:ty ),* $(,)?]
    ) => {
        #[doc = concat!("The ", $kind, " laws of scenes (`[contact] ", $kind, " = \"…\"`), by name: ")]
        #[doc = concat!("the list [`", stringify!($model), "`] has a variant for each.")]
        pub static $list: &[SubModelEntry] = &[
            $( $(#[$attr])* SubModelEntry::of::<$ty>(), )*
        ];

        #[doc = concat!("A registered ", $kind, " model, one variant per entry of [`", stringify!($list), "`].")]
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub enum $model {
            $(
                $(#[$attr])*
                #[doc = concat!("`", stringify!($ty), "`.")]
                $variant($ty),
            )*
        }

        #[doc = concat!("[`", stringify!($model), "`] bound to a pair.")]
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub enum $law {
            $(
                $(#[$attr])*
                #[doc = concat!("`", stringify!($ty), "` bound to a pair.")]
                $variant(<$ty as $Model>::Law),
            )*
        }

        impl $model {
            /// The registered law named `name` with its parameter values in declared order
            /// (checked by the law's [`Declared::from_values`]).
            pub fn from_declared(name: &str, values: &[f64]) -> Result<Self> {
                match name {
                    $(
                        $(#[$attr])*
                        n if n == <$ty as Declared>::DECLARATION.name => {
                            Ok(Self::$variant(<$ty as Declared>::from_values(values)?))
                        }
                    )*
                    _ => Err(ContactError::InvalidTable {
                        name: $kind,
                        reason: format!("no registered {} law is named `{name}`", $kind),
                    }),
                }
            }

            /// The model of a scene's validated choice.
            pub fn of(spec: &SubModelSpec) -> Result<Self> {
                Self::from_declared(spec.declaration.name, &spec.values)
            }

            /// The declaration of the model's law.
            pub fn declaration(&self) -> LawDeclaration {
                match self {
                    $( $(#[$attr])* Self::$variant(_) => <$ty as Declared>::DECLARATION, )*
                }
            }
        }

        impl $Model for $model {
            type Law = $law;
            fn bind(&self, pair: &ContactPair) -> Result<$law> {
                Ok(match self {
                    $( $(#[$attr])* Self::$variant(m) => $law::$variant(m.bind(pair)?), )*
                })
            }
        }
    };
}

/// The tangential laws of scenes, from their registry list: `list` names the entries,
/// `model`/`law` the generated enums, `history` the per-contact history every law's history is
/// held in ([`HistoryIn`]); then one `Variant: ModelType,` line per law.
macro_rules! tangential_laws {
    (
        list: $list:ident, model: $model:ident, law: $law:ident, history: $history:ty,
        laws: [$( $(#[$attr:meta])* $variant:ident: $ty:ty ),* $(,)?]
    ) => {
        sub_model_enums!("tangential", $list, $model, $law, TangentialModel,
            [$( $(#[$attr])* $variant: $ty ),*]);

        impl TangentialLaw for $law {
            type State = $history;
            #[inline(always)]
            fn update(&self, state: &mut $history, input: &TangentialInput) -> TangentialResponse {
                match self {
                    $(
                        $(#[$attr])*
                        Self::$variant(l) => {
                            <<<$ty as TangentialModel>::Law as TangentialLaw>::State as HistoryIn<$history>>
                                ::update_in(state, |s| l.update(s, input))
                        }
                    )*
                }
            }
            #[inline]
            fn elastic_energy(&self, state: &$history) -> f64 {
                match self {
                    $(
                        $(#[$attr])*
                        Self::$variant(l) => l.elastic_energy(
                            <<<$ty as TangentialModel>::Law as TangentialLaw>::State as HistoryIn<$history>>
                                ::read_in(state),
                        ),
                    )*
                }
            }
        }
    };
}

/// The damping laws of scenes, from their registry list (as [`tangential_laws!`]; a damping law
/// keeps no history).
macro_rules! damping_laws {
    (
        list: $list:ident, model: $model:ident, law: $law:ident,
        laws: [$( $(#[$attr:meta])* $variant:ident: $ty:ty ),* $(,)?]
    ) => {
        sub_model_enums!("damping", $list, $model, $law, DampingModel,
            [$( $(#[$attr])* $variant: $ty ),*]);

        impl DampingLaw for $law {
            #[inline]
            fn normal_coefficient(&self, response: &NormalResponse, overlap: f64) -> f64 {
                match self {
                    $( $(#[$attr])* Self::$variant(l) => l.normal_coefficient(response, overlap), )*
                }
            }
            #[inline]
            fn tangential_ratio(&self) -> f64 {
                match self {
                    $( $(#[$attr])* Self::$variant(l) => l.tangential_ratio(), )*
                }
            }
        }
    };
}

/// The rolling-resistance laws of scenes, from their registry list (as [`tangential_laws!`]).
/// The model enum also forwards [`RollingModel::resists`]: a scene whose rolling law cannot
/// give a torque runs without rolling history.
macro_rules! rolling_laws {
    (
        list: $list:ident, model: $model:ident, law: $law:ident, history: $history:ty,
        laws: [$( $(#[$attr:meta])* $variant:ident: $ty:ty ),* $(,)?]
    ) => {
        sub_model_enums!("rolling", $list, $model, $law, RollingModel,
            [$( $(#[$attr])* $variant: $ty ),*]);

        impl $model {
            /// Whether the model can give a torque ([`RollingModel::resists`]).
            pub fn resists(&self) -> bool {
                match self {
                    $( $(#[$attr])* Self::$variant(m) => m.resists(), )*
                }
            }
        }

        impl RollingLaw for $law {
            type State = $history;
            // Always inlined: called out of line, the law must compute every field of its
            // response, the energies the pair loop does not read among them.
            #[inline(always)]
            fn update(&self, state: &mut $history, input: &RollingInput) -> RollingResponse {
                match self {
                    $(
                        $(#[$attr])*
                        Self::$variant(l) => {
                            <<<$ty as RollingModel>::Law as RollingLaw>::State as HistoryIn<$history>>
                                ::update_in(state, |s| l.update(s, input))
                        }
                    )*
                }
            }
            #[inline]
            fn elastic_energy(&self, state: &$history) -> f64 {
                match self {
                    $(
                        $(#[$attr])*
                        Self::$variant(l) => l.elastic_energy(
                            <<<$ty as RollingModel>::Law as RollingLaw>::State as HistoryIn<$history>>
                                ::read_in(state),
                        ),
                    )*
                }
            }
            #[inline]
            fn dissipated_work(&self, state: &$history) -> f64 {
                match self {
                    $(
                        $(#[$attr])*
                        Self::$variant(l) => l.dissipated_work(
                            <<<$ty as RollingModel>::Law as RollingLaw>::State as HistoryIn<$history>>
                                ::read_in(state),
                        ),
                    )*
                }
            }
        }
    };
}

pub(crate) use {damping_laws, rolling_laws, sub_model_enums, tangential_laws};
