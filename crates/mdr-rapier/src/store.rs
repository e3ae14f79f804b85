//! The contact history store: one entry per touching pair, kept sorted by a deterministic pair
//! key, created at first touch and dropped when the pair separates.
//!
//! Each step the store is rebuilt by merging the (sorted) list of touching pairs with the
//! (sorted) previous entries. Two buffers are swapped, so once their capacity has grown to the
//! largest number of contacts no step allocates; memory stays proportional to the contacts.

use crate::error::Result;
use rapier3d_f64::prelude::ColliderHandle;

/// Deterministic key of an unordered collider pair: the two arena indices, smaller first.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct PairKey(pub u64);

impl PairKey {
    /// The key of the pair `{a, b}` (order does not matter).
    #[inline]
    pub fn new(a: ColliderHandle, b: ColliderHandle) -> Self {
        let i = a.into_raw_parts().0 as u64;
        let j = b.into_raw_parts().0 as u64;
        let (lo, hi) = if i <= j { (i, j) } else { (j, i) };
        PairKey((lo << 32) | hi)
    }
}

/// An entry of a [`ContactStore`].
pub trait Keyed {
    /// The entry's pair key.
    fn key(&self) -> PairKey;
}

/// Per-pair history entries sorted by [`PairKey`], with counters of created and removed entries.
#[derive(Debug, Clone)]
pub struct ContactStore<E> {
    entries: Vec<E>,
    scratch: Vec<E>,
    created: u64,
    removed: u64,
}

impl<E> Default for ContactStore<E> {
    fn default() -> Self {
        Self {
            entries: Vec::new(),
            scratch: Vec::new(),
            created: 0,
            removed: 0,
        }
    }
}

impl<E: Keyed> ContactStore<E> {
    /// An empty store.
    pub fn new() -> Self {
        Self::default()
    }

    /// Replace the entries by one per item of `touching` (sorted by strictly increasing key):
    /// an existing entry with the same key is kept and passed to `keep` with the item (its
    /// history survives), a missing one is made by `create`; entries whose key is absent are
    /// dropped (the pair separated).
    ///
    /// When the touching pairs are exactly the stored ones (the common case in a quasi-static
    /// bed) the entries are updated in place and nothing moves.
    pub fn merge<C, I>(
        &mut self,
        touching: I,
        key_of: impl Fn(&C) -> PairKey,
        mut create: impl FnMut(C) -> Result<E>,
        mut keep: impl FnMut(&mut E, C),
    ) -> Result<()>
    where
        I: IntoIterator<Item = C>,
        I::IntoIter: Clone,
    {
        let Self {
            entries,
            scratch,
            created,
            removed,
        } = self;
        let touching = touching.into_iter();
        if touching
            .clone()
            .map(|c| key_of(&c))
            .eq(entries.iter().map(|e| e.key()))
        {
            for (entry, item) in entries.iter_mut().zip(touching) {
                keep(entry, item);
            }
            return Ok(());
        }
        scratch.clear();
        let mut old = entries.drain(..).peekable();
        for item in touching {
            let key = key_of(&item);
            while old.peek().is_some_and(|e| e.key() < key) {
                old.next();
                *removed += 1;
            }
            match old.next_if(|e| e.key() == key) {
                Some(mut entry) => {
                    keep(&mut entry, item);
                    scratch.push(entry);
                }
                None => {
                    scratch.push(create(item)?);
                    *created += 1;
                }
            }
        }
        *removed += old.count() as u64;
        std::mem::swap(entries, scratch);
        Ok(())
    }

    /// The entries, sorted by key.
    pub fn entries(&self) -> &[E] {
        &self.entries
    }

    /// The entries, sorted by key, mutably (for the parallel force pass).
    pub fn entries_mut(&mut self) -> &mut [E] {
        &mut self.entries
    }

    /// The entry of a pair, if the pair touches.
    pub fn get(&self, key: PairKey) -> Option<&E> {
        self.entries
            .binary_search_by_key(&key, |e| e.key())
            .ok()
            .map(|i| &self.entries[i])
    }

    /// Number of entries (touching pairs).
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether the store is empty.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Entries created since the store was made.
    pub fn created(&self) -> u64 {
        self.created
    }

    /// Entries removed since the store was made.
    pub fn removed(&self) -> u64 {
        self.removed
    }

    /// Capacity of the entry buffer (for checking that memory stays bounded).
    pub fn capacity(&self) -> usize {
        self.entries.capacity().max(self.scratch.capacity())
    }

    /// Drop every entry.
    pub fn clear(&mut self) {
        self.removed += self.entries.len() as u64;
        self.entries.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug)]
    struct E(PairKey, u32);
    impl Keyed for E {
        fn key(&self) -> PairKey {
            self.0
        }
    }

    #[test]
    fn merge_keeps_creates_and_drops() {
        let mut store = ContactStore::<E>::new();
        let k = |i| PairKey(i);
        store
            .merge([1u64, 3, 5], |&i| k(i), |i| Ok(E(k(i), 0)), |e, _| e.1 += 1)
            .unwrap();
        store
            .merge(
                [3u64, 4, 5, 9],
                |&i| k(i),
                |i| Ok(E(k(i), 0)),
                |e, _| e.1 += 1,
            )
            .unwrap();
        let got: Vec<(u64, u32)> = store.entries().iter().map(|e| (e.0 .0, e.1)).collect();
        assert_eq!(got, vec![(3, 1), (4, 0), (5, 1), (9, 0)]);
        assert_eq!(store.created(), 5);
        assert_eq!(store.removed(), 1);
        store
            .merge(
                std::iter::empty::<u64>(),
                |&i| k(i),
                |i| Ok(E(k(i), 0)),
                |_, _| {},
            )
            .unwrap();
        assert!(store.is_empty());
        assert_eq!(store.removed(), 5);
    }
}
