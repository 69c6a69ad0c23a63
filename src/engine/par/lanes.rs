//! [`L`]: four f64 lanes evaluated together, the unit of the SPH pair loop's batches.
//!
//! Every operation is the IEEE operation of each lane, so a lane gives the bits of the scalar
//! expression written in the same order. Where the CPU has AVX (the release build targets the
//! host) each operation is one 256-bit instruction; left to itself the compiler mixed 128- and
//! 256-bit pieces and spilled them in halves that were reloaded whole, a store-forwarding stall
//! that cost about a tenth of the SPH loop's time.

use std::ops::{Add, AddAssign, Div, Index, IndexMut, Mul, Neg, Sub};

/// Lanes per batch (one AVX register of f64; 8 measured slower).
pub const LANES: usize = 4;

/// One value per lane; lane `l` is `x[l]`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C, align(32))]
pub struct L(pub [f64; LANES]);

/// A lane array from a per-lane expression.
#[inline(always)]
pub fn lanes(f: impl Fn(usize) -> f64) -> L {
    L(std::array::from_fn(f))
}

#[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
mod imp {
    use super::L;
    use std::arch::x86_64::*;

    #[inline(always)]
    pub fn load(x: &L) -> __m256d {
        // SAFETY: AVX is enabled at compile time; L is 32-byte aligned and holds four f64
        unsafe { _mm256_load_pd(x.0.as_ptr()) }
    }
    #[inline(always)]
    pub fn store(v: __m256d) -> L {
        let mut out = L([0.0; 4]);
        // SAFETY: as in load
        unsafe { _mm256_store_pd(out.0.as_mut_ptr(), v) };
        out
    }
    macro_rules! binary {
        ($name:ident, $intr:ident) => {
            #[inline(always)]
            pub fn $name(a: &L, b: &L) -> L {
                // SAFETY: AVX is enabled at compile time
                store(unsafe { $intr(load(a), load(b)) })
            }
        };
    }
    binary!(add, _mm256_add_pd);
    binary!(sub, _mm256_sub_pd);
    binary!(mul, _mm256_mul_pd);
    binary!(div, _mm256_div_pd);
    #[inline(always)]
    pub fn splat(x: f64) -> L {
        // SAFETY: AVX is enabled at compile time
        store(unsafe { _mm256_set1_pd(x) })
    }
    #[inline(always)]
    pub fn sqrt(a: &L) -> L {
        // SAFETY: AVX is enabled at compile time
        store(unsafe { _mm256_sqrt_pd(load(a)) })
    }
    #[inline(always)]
    pub fn neg(a: &L) -> L {
        // flipping the sign bit is what `-x` does to an f64
        // SAFETY: AVX is enabled at compile time
        store(unsafe { _mm256_xor_pd(load(a), _mm256_set1_pd(-0.0)) })
    }
    #[inline(always)]
    pub fn select_lt(a: &L, b: &L, yes: &L) -> L {
        // ordered compare: a NaN lane is "not less", as in the scalar `a < b`
        // SAFETY: AVX is enabled at compile time
        store(unsafe { _mm256_and_pd(_mm256_cmp_pd::<_CMP_LT_OQ>(load(a), load(b)), load(yes)) })
    }
    #[inline(always)]
    pub fn lt_bits(a: &L, b: &L) -> u32 {
        // SAFETY: AVX is enabled at compile time
        unsafe { _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_LT_OQ>(load(a), load(b))) as u32 }
    }
    /// All-ones lanes where a < b (ordered: NaN is not less).
    #[inline(always)]
    pub fn lt_mask(a: &L, b: &L) -> L {
        // SAFETY: AVX is enabled at compile time
        store(unsafe { _mm256_cmp_pd::<_CMP_LT_OQ>(load(a), load(b)) })
    }
    /// All-ones lanes where a != b (unordered: NaN is unequal, as the scalar `!=`).
    #[inline(always)]
    pub fn ne_mask(a: &L, b: &L) -> L {
        // SAFETY: AVX is enabled at compile time
        store(unsafe { _mm256_cmp_pd::<_CMP_NEQ_UQ>(load(a), load(b)) })
    }
    binary!(and_bits, _mm256_and_pd);
    /// Bit l set where lane l has its sign bit set (a mask lane that is true).
    #[inline(always)]
    pub fn sign_bits(a: &L) -> u32 {
        // SAFETY: AVX is enabled at compile time
        unsafe { _mm256_movemask_pd(load(a)) as u32 }
    }
    /// Per lane: `yes` where the mask lane is all ones, else `no`.
    #[inline(always)]
    pub fn blend(m: &L, yes: &L, no: &L) -> L {
        // SAFETY: AVX is enabled at compile time
        store(unsafe { _mm256_blendv_pd(load(no), load(yes), load(m)) })
    }
    #[inline(always)]
    pub fn abs(a: &L) -> L {
        // clearing the sign bit is what f64::abs does
        // SAFETY: AVX is enabled at compile time
        store(unsafe { _mm256_andnot_pd(_mm256_set1_pd(-0.0), load(a)) })
    }
    /// Rows to columns of a 4x4 block: `out[k][l] = m[l][k]`.
    #[inline(always)]
    pub fn transpose(m: [&[f64; 4]; 4]) -> [L; 4] {
        // SAFETY: AVX is enabled at compile time; every row holds four f64
        unsafe {
            let r = [_mm256_loadu_pd(m[0].as_ptr()), _mm256_loadu_pd(m[1].as_ptr()), _mm256_loadu_pd(m[2].as_ptr()), _mm256_loadu_pd(m[3].as_ptr())];
            let t0 = _mm256_unpacklo_pd(r[0], r[1]);
            let t1 = _mm256_unpackhi_pd(r[0], r[1]);
            let t2 = _mm256_unpacklo_pd(r[2], r[3]);
            let t3 = _mm256_unpackhi_pd(r[2], r[3]);
            [
                store(_mm256_permute2f128_pd(t0, t2, 0x20)),
                store(_mm256_permute2f128_pd(t1, t3, 0x20)),
                store(_mm256_permute2f128_pd(t0, t2, 0x31)),
                store(_mm256_permute2f128_pd(t1, t3, 0x31)),
            ]
        }
    }
}

#[cfg(not(all(target_arch = "x86_64", target_feature = "avx")))]
mod imp {
    use super::{lanes, L};

    #[inline(always)]
    pub fn add(a: &L, b: &L) -> L {
        lanes(|l| a.0[l] + b.0[l])
    }
    #[inline(always)]
    pub fn sub(a: &L, b: &L) -> L {
        lanes(|l| a.0[l] - b.0[l])
    }
    #[inline(always)]
    pub fn mul(a: &L, b: &L) -> L {
        lanes(|l| a.0[l] * b.0[l])
    }
    #[inline(always)]
    pub fn div(a: &L, b: &L) -> L {
        lanes(|l| a.0[l] / b.0[l])
    }
    #[inline(always)]
    pub fn splat(x: f64) -> L {
        L([x; 4])
    }
    #[inline(always)]
    pub fn sqrt(a: &L) -> L {
        lanes(|l| a.0[l].sqrt())
    }
    #[inline(always)]
    pub fn neg(a: &L) -> L {
        lanes(|l| -a.0[l])
    }
    #[inline(always)]
    pub fn select_lt(a: &L, b: &L, yes: &L) -> L {
        lanes(|l| if a.0[l] < b.0[l] { yes.0[l] } else { 0.0 })
    }
    #[inline(always)]
    pub fn lt_bits(a: &L, b: &L) -> u32 {
        (0..4).map(|l| ((a.0[l] < b.0[l]) as u32) << l).sum()
    }
    fn bits(b: bool) -> f64 {
        f64::from_bits(if b { u64::MAX } else { 0 })
    }
    #[inline(always)]
    pub fn lt_mask(a: &L, b: &L) -> L {
        lanes(|l| bits(a.0[l] < b.0[l]))
    }
    #[inline(always)]
    pub fn ne_mask(a: &L, b: &L) -> L {
        lanes(|l| bits(a.0[l] != b.0[l]))
    }
    #[inline(always)]
    pub fn and_bits(a: &L, b: &L) -> L {
        lanes(|l| f64::from_bits(a.0[l].to_bits() & b.0[l].to_bits()))
    }
    #[inline(always)]
    pub fn blend(m: &L, yes: &L, no: &L) -> L {
        lanes(|l| if m.0[l].to_bits() >> 63 != 0 { yes.0[l] } else { no.0[l] })
    }
    #[inline(always)]
    pub fn sign_bits(a: &L) -> u32 {
        (0..4).map(|l| ((a.0[l].to_bits() >> 63) as u32) << l).sum()
    }
    #[inline(always)]
    pub fn abs(a: &L) -> L {
        lanes(|l| a.0[l].abs())
    }
    #[inline(always)]
    pub fn transpose(m: [&[f64; 4]; 4]) -> [L; 4] {
        std::array::from_fn(|k| lanes(|l| m[l][k]))
    }
}

impl L {
    /// The same value in every lane.
    #[inline(always)]
    pub fn splat(x: f64) -> L {
        imp::splat(x)
    }
    #[inline(always)]
    pub fn sqrt(&self) -> L {
        imp::sqrt(self)
    }
    /// Per lane: `yes` where `self < other`, else +0 (a NaN lane is not less).
    #[inline(always)]
    pub fn lt_or_zero(&self, other: &L, yes: &L) -> L {
        imp::select_lt(self, other, yes)
    }
    /// Bit l set where lane l of `self` is less than that of `other` (a NaN lane is not less).
    #[inline(always)]
    pub fn lt_bits(&self, other: &L) -> u32 {
        imp::lt_bits(self, other)
    }
}

/// A number the physics is written over once: `f64` for one pair, [`L`] for a batch. Every
/// operation is the IEEE operation per lane, and a branch of the scalar code is a [`Real::select`]
/// (both sides computed, one kept), so a formula gives the same bits either way. Constants enter
/// with [`Real::splat`] (`T::splat(2.0) * x` is what `2.0 * x` is for a lane type).
pub trait Real: Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self> + Neg<Output = Self> + AddAssign {
    /// The truth of a comparison, per lane.
    type Mask: Copy + std::ops::BitAnd<Output = Self::Mask>;
    fn splat(x: f64) -> Self;
    fn sqrt(self) -> Self;
    fn abs(self) -> Self;
    /// `self < other` (false for NaN).
    fn lt(self, other: Self) -> Self::Mask;
    /// `self != other` (true for NaN).
    fn ne(self, other: Self) -> Self::Mask;
    /// `if m { yes } else { no }`, per lane.
    fn select(m: Self::Mask, yes: Self, no: Self) -> Self;
    /// Whether the mask is true in any lane (a branch that no lane takes can be skipped).
    fn any(m: Self::Mask) -> bool;
    /// `f` of each lane (a library function with no lane form, e.g. the C library's `acos`).
    fn map(self, f: impl Fn(f64) -> f64) -> Self;
}

impl Real for f64 {
    type Mask = bool;
    #[inline(always)]
    fn splat(x: f64) -> f64 {
        x
    }
    #[inline(always)]
    fn sqrt(self) -> f64 {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> f64 {
        f64::abs(self)
    }
    #[inline(always)]
    fn lt(self, other: f64) -> bool {
        self < other
    }
    #[inline(always)]
    fn ne(self, other: f64) -> bool {
        self != other
    }
    #[inline(always)]
    fn select(m: bool, yes: f64, no: f64) -> f64 {
        if m {
            yes
        } else {
            no
        }
    }
    #[inline(always)]
    fn any(m: bool) -> bool {
        m
    }
    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> f64 {
        f(self)
    }
}

/// A per-lane truth value of [`L`]: all bits set where true.
#[derive(Clone, Copy, Debug)]
pub struct Mask(L);

impl std::ops::BitAnd for Mask {
    type Output = Mask;
    #[inline(always)]
    fn bitand(self, o: Mask) -> Mask {
        Mask(imp::and_bits(&self.0, &o.0))
    }
}

impl Real for L {
    type Mask = Mask;
    #[inline(always)]
    fn splat(x: f64) -> L {
        imp::splat(x)
    }
    #[inline(always)]
    fn sqrt(self) -> L {
        imp::sqrt(&self)
    }
    #[inline(always)]
    fn abs(self) -> L {
        imp::abs(&self)
    }
    #[inline(always)]
    fn lt(self, other: L) -> Mask {
        Mask(imp::lt_mask(&self, &other))
    }
    #[inline(always)]
    fn ne(self, other: L) -> Mask {
        Mask(imp::ne_mask(&self, &other))
    }
    #[inline(always)]
    fn select(m: Mask, yes: L, no: L) -> L {
        imp::blend(&m.0, &yes, &no)
    }
    #[inline(always)]
    fn any(m: Mask) -> bool {
        imp::sign_bits(&m.0) != 0
    }
    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> L {
        lanes(|l| f(self.0[l]))
    }
}

/// `f(l)` for the lanes `0..n` (n <= LANES) in order. A full batch runs with the constant count
/// [`LANES`], which the compiler unrolls: with the count a variable, a running sum the calls add to
/// lived in a stack slot.
#[inline(always)]
pub fn for_each_lane(n: usize, mut f: impl FnMut(usize)) {
    if n == LANES {
        (0..LANES).for_each(&mut f);
    } else {
        (0..n).for_each(f);
    }
}

/// Rows to columns of a 4x4 block: `out[k][l] = m[l][k]`.
#[inline(always)]
pub fn transpose4(m: [&[f64; 4]; 4]) -> [L; 4] {
    imp::transpose(m)
}

macro_rules! operator {
    ($tr:ident, $method:ident, $f:path) => {
        impl $tr for L {
            type Output = L;
            #[inline(always)]
            fn $method(self, o: L) -> L {
                $f(&self, &o)
            }
        }
        /// The scalar in every lane, on the left (`2.0 * x` keeps its order of operands).
        impl $tr<L> for f64 {
            type Output = L;
            #[inline(always)]
            fn $method(self, o: L) -> L {
                $f(&L::splat(self), &o)
            }
        }
        impl $tr<f64> for L {
            type Output = L;
            #[inline(always)]
            fn $method(self, o: f64) -> L {
                $f(&self, &L::splat(o))
            }
        }
    };
}
operator!(Add, add, imp::add);
operator!(Sub, sub, imp::sub);
operator!(Mul, mul, imp::mul);
operator!(Div, div, imp::div);

impl AddAssign for L {
    #[inline(always)]
    fn add_assign(&mut self, o: L) {
        *self = imp::add(self, &o);
    }
}

impl Neg for L {
    type Output = L;
    #[inline(always)]
    fn neg(self) -> L {
        imp::neg(&self)
    }
}

impl Index<usize> for L {
    type Output = f64;
    #[inline(always)]
    fn index(&self, l: usize) -> &f64 {
        &self.0[l]
    }
}

impl IndexMut<usize> for L {
    #[inline(always)]
    fn index_mut(&mut self, l: usize) -> &mut f64 {
        &mut self.0[l]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every operation gives each lane the bits of the scalar operation, signed zeros and NaN
    /// included.
    #[test]
    fn lanes_are_the_scalar_operations() {
        let a = L([1.5, -0.0, f64::NAN, 3.0e-300]);
        let b = L([0.1, 0.0, 2.0, -7.25e10]);
        let same = |v: L, f: &dyn Fn(f64, f64) -> f64| {
            for l in 0..LANES {
                let s = f(a[l], b[l]);
                assert!(v[l].to_bits() == s.to_bits() || (v[l].is_nan() && s.is_nan()), "lane {l}: {} vs {}", v[l], s);
            }
        };
        same(a + b, &|x, y| x + y);
        same(a - b, &|x, y| x - y);
        same(a * b, &|x, y| x * y);
        same(a / b, &|x, y| x / y);
        same(-a, &|x, _| -x);
        same(2.0 * a, &|x, _| 2.0 * x);
        same(a.sqrt(), &|x, _| x.sqrt());
        same(b.lt_or_zero(&L::splat(0.0), &a), &|x, y| if y < 0.0 { x } else { 0.0 });
        assert_eq!(L([1.0, f64::NAN, -2.0, 5.0]).lt_bits(&L::splat(2.0)), 0b0101);
    }

    /// The comparisons and selects of [`Real`] on lanes are the scalar ones, NaN included.
    #[test]
    fn real_masks_are_the_scalar_comparisons() {
        let a = L([1.5, -0.0, f64::NAN, 3.0]);
        let b = L([0.1, 0.0, 2.0, 3.0]);
        let yes = L([10.0, 20.0, 30.0, 40.0]);
        let no = L([-1.0, -2.0, -3.0, -4.0]);
        let lt = <L as Real>::select(a.lt(b), yes, no);
        let ne = <L as Real>::select(a.ne(b), yes, no);
        let both = <L as Real>::select(a.lt(b) & a.ne(b), yes, no);
        for l in 0..LANES {
            assert_eq!(lt[l], f64::select(a[l].lt(b[l]), yes[l], no[l]), "lt lane {l}");
            assert_eq!(ne[l], f64::select(Real::ne(a[l], b[l]), yes[l], no[l]), "ne lane {l}");
            assert_eq!(both[l], f64::select(a[l] < b[l] && a[l] != b[l], yes[l], no[l]), "and lane {l}");
            let (x, y) = (Real::abs(a)[l], a[l].abs());
            assert!(x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()));
        }
    }

    #[test]
    fn transpose_swaps_rows_and_columns() {
        let rows = [[0.0, 1.0, 2.0, 3.0], [4.0, 5.0, 6.0, 7.0], [8.0, 9.0, 10.0, 11.0], [12.0, 13.0, 14.0, 15.0]];
        let t = transpose4([&rows[0], &rows[1], &rows[2], &rows[3]]);
        for k in 0..4 {
            for l in 0..4 {
                assert_eq!(t[k][l], rows[l][k]);
            }
        }
    }
}
