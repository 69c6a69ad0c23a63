//! Neighbour entries that per-atom arrays can be read through without a bounds check.
//!
//! A list's entries are checked once, when the list is made ([`Entries::new`]: every index
//! below the list's `bound`, the number of owned + ghost atoms it was built for). A loop then
//! opens a [`scope`] with a bound: inside it, the entries of any list made for no more atoms
//! ([`Entries::view`]) become [`Entry`] values, and every array at least that long becomes a
//! [`Reader`] that an `Entry` indexes unchecked. The scope's brand (an invariant lifetime, one
//! per call of [`scope`]) keeps an entry of one scope from indexing a reader of another, so the
//! two checks (the list's bound, the reader's length) are enough.

use std::marker::PhantomData;

/// Low bits of an entry that hold the atom index; the two above it hold the special-bond level.
pub const INDEX_BITS: u32 = 30;
pub const INDEX_MASK: u32 = (1 << INDEX_BITS) - 1;

/// The brand of one scope: invariant in `'id`, so no two scopes share it.
type Brand<'id> = PhantomData<fn(&'id ()) -> &'id ()>;

/// A list's raw entries (index in the low [`INDEX_BITS`], special level above), each index
/// proven below `bound` when made.
#[derive(Clone, Debug, Default)]
pub struct Entries {
    raw: Vec<u32>,
    bound: usize,
}

impl Entries {
    /// Check every index against `bound` (the atoms the list indexes); panics on an entry
    /// beyond it, which is a bug of the list's builder.
    pub fn new(raw: Vec<u32>, bound: usize) -> Entries {
        let max = raw.iter().fold(0u32, |m, &e| m.max(e & INDEX_MASK));
        assert!(raw.is_empty() || (max as usize) < bound, "neighbour entry {max} beyond the {bound} atoms of the list");
        Entries { raw, bound }
    }
    pub fn raw(&self) -> &[u32] {
        &self.raw
    }
    pub fn len(&self) -> usize {
        self.raw.len()
    }
    pub fn is_empty(&self) -> bool {
        self.raw.is_empty()
    }
    pub fn capacity(&self) -> usize {
        self.raw.capacity()
    }
    /// Clear the special-bond level of entry `k` (its index, checked when made, stays).
    pub fn clear_level(&mut self, k: usize) {
        self.raw[k] &= INDEX_MASK;
    }
    /// The atoms the entries may index.
    pub fn bound(&self) -> usize {
        self.bound
    }
    /// Entries `r` as values of scope `s`; panics when the list was made for more atoms than
    /// the scope's bound.
    #[inline]
    pub fn view<'id>(&self, s: &Scope<'id>, r: std::ops::Range<usize>) -> &[Entry<'id>] {
        assert!(self.bound <= s.bound, "a list of {} atoms read in a scope of {}", self.bound, s.bound);
        let raw = &self.raw[r];
        // SAFETY: Entry is a transparent u32 (the brand has no size)
        unsafe { std::slice::from_raw_parts(raw.as_ptr().cast::<Entry<'id>>(), raw.len()) }
    }
}

/// One neighbour entry of scope `'id`: its index is below the scope's bound.
#[derive(Clone, Copy, Debug)]
#[repr(transparent)]
pub struct Entry<'id> {
    raw: u32,
    brand: Brand<'id>,
}

impl Entry<'_> {
    /// The atom index.
    #[inline(always)]
    pub fn index(self) -> usize {
        (self.raw & INDEX_MASK) as usize
    }
    /// The entry with its special-bond level.
    #[inline(always)]
    pub fn raw(self) -> u32 {
        self.raw
    }
}

/// A bound for the entries and readers made in one call of [`scope`].
#[derive(Clone, Copy, Debug)]
pub struct Scope<'id> {
    bound: usize,
    brand: Brand<'id>,
}

/// Run `f` in a fresh scope of `bound` atoms.
pub fn scope<R>(bound: usize, f: impl for<'id> FnOnce(Scope<'id>) -> R) -> R {
    f(Scope { bound, brand: PhantomData })
}

impl<'id> Scope<'id> {
    /// `data` read by the scope's entries; panics when it is shorter than the bound.
    #[inline]
    pub fn reader<'a, T>(&self, data: &'a [T]) -> Reader<'id, 'a, T> {
        assert!(data.len() >= self.bound, "an array of {} values read by entries of {} atoms", data.len(), self.bound);
        Reader { data, brand: PhantomData }
    }
}

/// Per-atom values indexed by the entries of one scope, without bounds checks.
#[derive(Debug)]
pub struct Reader<'id, 'a, T> {
    data: &'a [T],
    brand: Brand<'id>,
}

impl<T> Clone for Reader<'_, '_, T> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<T> Copy for Reader<'_, '_, T> {}

impl<'id, 'a, T> Reader<'id, 'a, T> {
    #[inline(always)]
    pub fn get(self, e: Entry<'id>) -> &'a T {
        // SAFETY: e.index() < the scope's bound (the list's check and `view`'s) <= data.len()
        // (`reader`'s check), and the brand ties e to this scope
        unsafe { self.data.get_unchecked(e.index()) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entries_read_through_a_reader() {
        let e = Entries::new(vec![2, 0, (1 << INDEX_BITS) | 1], 3);
        let data = [10.0, 11.0, 12.0];
        let got: Vec<f64> = scope(3, |s| {
            let r = s.reader(&data);
            e.view(&s, 0..3).iter().map(|&j| *r.get(j)).collect()
        });
        assert_eq!(got, [12.0, 10.0, 11.0]);
    }

    #[test]
    #[should_panic(expected = "beyond the 3 atoms")]
    fn an_entry_beyond_the_bound_is_refused_when_made() {
        Entries::new(vec![0, 3], 3);
    }

    #[test]
    #[should_panic(expected = "an array of 2 values")]
    fn a_short_array_is_refused() {
        scope(3, |s| {
            s.reader(&[0.0, 1.0]);
        });
    }

    #[test]
    #[should_panic(expected = "a list of 4 atoms read in a scope of 3")]
    fn a_list_for_more_atoms_than_the_scope_is_refused() {
        let e = Entries::new(vec![3], 4);
        scope(3, |s| {
            e.view(&s, 0..1);
        });
    }
}
