//! Normal sub-models per material pair: a coupling binds the contacts of two materials with
//! their own normal model (the adhesive MDR law with the pair's work of adhesion `Δγ_ij`, say)
//! in place of its contact model's, and every other pair with the model's. The table is read
//! where laws are bound (once per species pair on the neighbour-list path, once per new
//! contact on the rapier pipeline path, once per impact in restitution mode), never per contact
//! update: the pair loop runs one law type, monomorphised, whatever value each pair carries.

use crate::particles::MaterialHandle;
use mdr_contact::damping::DampingModel;
use mdr_contact::model::{ContactLaw, ContactModel};
use mdr_contact::normal::NormalModel;
use mdr_contact::tangential::TangentialModel;
use mdr_contact::ContactPair;
use std::collections::BTreeMap;

/// The normal sub-models set per unordered material pair.
#[derive(Debug, Clone)]
pub(crate) struct PairNormals<N> {
    models: BTreeMap<(u32, u32), N>,
}

impl<N> Default for PairNormals<N> {
    fn default() -> Self {
        Self {
            models: BTreeMap::new(),
        }
    }
}

/// The table's key of the unordered pair `(a, b)`.
fn key(a: MaterialHandle, b: MaterialHandle) -> (u32, u32) {
    (a.0.min(b.0), a.0.max(b.0))
}

impl<N: NormalModel> PairNormals<N> {
    /// Bind the pairs of materials `a` and `b` (either order) with `normal`.
    pub(crate) fn set(&mut self, a: MaterialHandle, b: MaterialHandle, normal: N) {
        self.models.insert(key(a, b), normal);
    }

    /// The normal model set for materials `a` and `b`, if any.
    pub(crate) fn get(&self, a: MaterialHandle, b: MaterialHandle) -> Option<&N> {
        self.models.get(&key(a, b))
    }

    /// `model` bound to `pair` of materials `a` and `b`, with the normal model set for the
    /// pair in place of `model.normal` where there is one.
    pub(crate) fn bind<T: TangentialModel, D: DampingModel>(
        &self,
        model: &ContactModel<N, T, D>,
        a: MaterialHandle,
        b: MaterialHandle,
        pair: &ContactPair,
    ) -> mdr_contact::Result<ContactLaw<N::Law, T::Law, D::Law>> {
        match self.get(a, b) {
            Some(normal) => Ok(ContactLaw {
                normal: normal.bind(pair)?,
                tangential: model.tangential.bind(pair)?,
                damping: model.damping.bind(pair)?,
            }),
            None => model.bind(pair),
        }
    }
}
