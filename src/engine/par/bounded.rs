//! Neighbour entries that per-atom arrays can be read through without a bounds check.
//!
//! A list's entries are checked once, when the list is made ([`Entries::new`]: every index
//! below the list's `bound`, the number of owned + ghost atoms it was built for). A loop then
//! opens a [`scope`] with a bound: inside it, the entries of any list made for no more atoms
//! ([`Entries::view`]) become [`Entry`] values, and every array at least that long becomes a
//! [`Reader`] that an `Entry` indexes unchecked. The scope's brand (an invariant lifetime, one
//! per call of [`scope`]) keeps an entry of one scope from indexing a reader of another, so the
//! two checks (the list's bound, the reader's length) are enough.
//!
//! Writes work the same way, for a task of the slab schedule ([`super::slab_phase`]). A list
//! also records, when made, the span of its owned entries (indices below its owned count). A
//! task opens [`scope_writing`] with the owned count and the atoms of its window; a list viewed
//! there must have its owned entries inside that span ([`Entries::view`]), so an entry the scope
//! finds owned ([`Scope::owned`]) writes into a [`Writer`] on that window unchecked. The check
//! is one comparison of spans per list and task instead of one per write.

use super::AtomsMut;
use std::marker::PhantomData;
use std::ops::{Deref, DerefMut, Range};

/// Low bits of an entry that hold the atom index; the two above it hold the special-bond level.
pub const INDEX_BITS: u32 = 30;
pub const INDEX_MASK: u32 = (1 << INDEX_BITS) - 1;

/// The brand of one scope: invariant in `'id`, so no two scopes share it.
type Brand<'id> = PhantomData<fn(&'id ()) -> &'id ()>;

/// A list's raw entries (index in the low [`INDEX_BITS`], special level above), each index
/// proven below `bound` when made, and its entries below `owned` proven inside `span`.
#[derive(Clone, Debug, Default)]
pub struct Entries {
    raw: Vec<u32>,
    bound: usize,
    owned: usize,
    /// The smallest and one past the largest index below `owned` (empty: none is).
    span: Range<usize>,
}

impl Entries {
    /// Check every index against `bound` (the atoms the list indexes) and note the span of the
    /// indices below `owned` (the owned atoms); panics on an entry beyond `bound`, which is a
    /// bug of the list's builder.
    pub fn new(raw: Vec<u32>, owned: usize, bound: usize) -> Entries {
        let (max, lo, hi) = raw.iter().fold((0u32, u32::MAX, 0u32), |(m, lo, hi), &e| {
            let j = e & INDEX_MASK;
            // branch-free: about half the entries of an SPH list are owned
            let own = (j as usize) < owned;
            (m.max(j), if own { lo.min(j) } else { lo }, if own { hi.max(j + 1) } else { hi })
        });
        assert!(raw.is_empty() || (max as usize) < bound, "neighbour entry {max} beyond the {bound} atoms of the list");
        let span = if lo < hi { lo as usize..hi as usize } else { 0..0 };
        Entries { raw, bound, owned, span }
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
    /// The owned atoms the list was made for.
    pub fn owned(&self) -> usize {
        self.owned
    }
    /// Entries `r` as values of scope `s`; panics when the list was made for more atoms than
    /// the scope's bound, or, in a scope that writes, for fewer owned atoms or with an owned
    /// entry outside the scope's span.
    #[inline]
    pub fn view<'id>(&self, s: &Scope<'id>, r: Range<usize>) -> &[Entry<'id>] {
        assert!(self.bound <= s.bound, "a list of {} atoms read in a scope of {}", self.bound, s.bound);
        let inside = self.span.is_empty() || (s.lo <= self.span.start && self.span.end <= s.hi);
        assert!(s.owned == 0 || (s.owned <= self.owned && inside), "a list of {} owned atoms ({:?}) written in a scope of {} ({}..{})", self.owned, self.span, s.owned, s.lo, s.hi);
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

/// A bound for the entries and readers made in one call of [`scope`] (or [`scope_writing`]:
/// with the owned count and the span `lo..hi` its owned entries lie in).
#[derive(Clone, Copy, Debug)]
pub struct Scope<'id> {
    bound: usize,
    owned: usize,
    lo: usize,
    hi: usize,
    brand: Brand<'id>,
}

/// Run `f` in a fresh scope of `bound` atoms that reads only.
pub fn scope<R>(bound: usize, f: impl for<'id> FnOnce(Scope<'id>) -> R) -> R {
    f(Scope { bound, owned: 0, lo: 0, hi: 0, brand: PhantomData })
}

/// Run `f` in a fresh scope of `bound` atoms whose entries below `owned` write to the atoms
/// `span` (a task's window; lists whose owned entries lie elsewhere are refused by `view`).
pub fn scope_writing<R>(bound: usize, owned: usize, span: Range<usize>, f: impl for<'id> FnOnce(Scope<'id>) -> R) -> R {
    f(Scope { bound, owned, lo: span.start, hi: span.end, brand: PhantomData })
}

/// An entry of scope `'id` below the scope's owned count: inside the scope's span.
#[derive(Clone, Copy, Debug)]
pub struct Owned<'id> {
    index: usize,
    brand: Brand<'id>,
}

impl Owned<'_> {
    #[inline(always)]
    pub fn index(self) -> usize {
        self.index
    }
}

impl<'id> Scope<'id> {
    /// `e` as an owned atom of the scope, or None for a ghost.
    #[inline(always)]
    pub fn owned(&self, e: Entry<'id>) -> Option<Owned<'id>> {
        let j = e.index();
        (j < self.owned).then_some(Owned { index: j, brand: PhantomData })
    }
    /// A window the scope's owned entries write to; panics when it does not cover the span.
    #[inline]
    pub fn writer<'a, T>(&self, w: AtomsMut<'a, T>) -> Writer<'id, 'a, T> {
        let r = w.range();
        assert!(r.start <= self.lo && self.hi <= r.end, "a window on atoms {r:?} written by entries of atoms {}..{}", self.lo, self.hi);
        Writer { window: w, brand: PhantomData }
    }
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

/// A window on per-atom values ([`AtomsMut`]) that the owned entries of one scope write
/// without bounds checks; indexed by atom index (checked) as the window otherwise.
pub struct Writer<'id, 'a, T> {
    window: AtomsMut<'a, T>,
    brand: Brand<'id>,
}

impl<'id, T> Writer<'id, '_, T> {
    #[inline(always)]
    pub fn at(&mut self, o: Owned<'id>) -> &mut T {
        let w = &mut self.window;
        // SAFETY: o.index() < the scope's owned count <= the list's (`view`'s check), so it lies
        // in the list's owned span, inside the scope's lo..hi (`view`), inside the window
        // start..start + data.len() (`writer`'s check); the brand ties o to this scope
        unsafe { w.data.get_unchecked_mut(o.index() - w.start) }
    }
}

impl<'a, T> Deref for Writer<'_, 'a, T> {
    type Target = AtomsMut<'a, T>;
    fn deref(&self) -> &AtomsMut<'a, T> {
        &self.window
    }
}

impl<T> DerefMut for Writer<'_, '_, T> {
    fn deref_mut(&mut self) -> &mut Self::Target {
        &mut self.window
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::par::Split;

    #[test]
    fn entries_read_through_a_reader() {
        let e = Entries::new(vec![2, 0, (1 << INDEX_BITS) | 1], 3, 3);
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
        Entries::new(vec![0, 3], 3, 3);
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
        let e = Entries::new(vec![3], 4, 4);
        scope(3, |s| {
            e.view(&s, 0..1);
        });
    }

    /// Owned entries write into a window covering their span; ghosts are not owned.
    #[test]
    fn owned_entries_write_through_a_writer() {
        // atoms 0..6 owned, 6..8 ghosts; the chunk's owned entries lie in 2..5
        let e = Entries::new(vec![2, 4, 6, 3, 7], 6, 8);
        let mut acc = vec![0.0; 6];
        let (_, rest) = AtomsMut::new(&mut acc).split(2, 0);
        scope_writing(8, 6, rest.range(), |s| {
            let mut w = s.writer(rest);
            for &j in e.view(&s, 0..5) {
                if let Some(o) = s.owned(j) {
                    *w.at(o) += j.index() as f64;
                }
            }
        });
        assert_eq!(acc, [0.0, 0.0, 2.0, 3.0, 4.0, 0.0]);
    }

    #[test]
    #[should_panic(expected = "written in a scope of 6 (3..6)")]
    fn a_list_with_owned_entries_outside_the_span_is_refused() {
        let e = Entries::new(vec![2, 4], 6, 8);
        scope_writing(8, 6, 3..6, |s| {
            e.view(&s, 0..2);
        });
    }

    #[test]
    #[should_panic(expected = "written in a scope of 7")]
    fn a_list_made_for_fewer_owned_atoms_is_refused() {
        let e = Entries::new(vec![2, 6], 6, 8);
        scope_writing(8, 7, 0..8, |s| {
            e.view(&s, 0..2);
        });
    }

    #[test]
    #[should_panic(expected = "a window on atoms 3..6 written by entries of atoms 2..6")]
    fn a_window_short_of_the_span_is_refused() {
        let mut acc = vec![0.0; 6];
        let (_, rest) = AtomsMut::new(&mut acc).split(3, 0);
        scope_writing(8, 6, 2..6, |s| {
            s.writer(rest);
        });
    }
}
