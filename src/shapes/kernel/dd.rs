//! Double-double numbers: an f64 pair `hi + lo` that carries about 106 bits, built from
//! the error-free transformations of Knuth (two-sum) and Dekker (two-product).
//!
//! The accurate kernel evaluates a quadric at a trial point (the residual of one
//! refinement step), where the terms cancel down to a small number and f64 would keep
//! none of its digits, with sums of exact products ([`sum_as_f64`]); a general quadric's
//! centred constants are computed once, at load, with [`Dd`] arithmetic.
//! [`two_prod`] takes the product's rounding error from
//! a fused multiply-add, which is exact on every machine: the kernel runs its refinement
//! in a copy compiled for the FMA instruction when the CPU has one (checked once, at run
//! time), and otherwise `mul_add` calls the C library's `fma`, slower, same bits. In
//! WebAssembly, which has no such instruction, Dekker's split gives the same bits.

use std::ops::{Add, Mul, Neg, Sub};

/// `hi + lo` with |lo| <= ulp(hi) / 2.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Dd {
    /// The leading f64.
    pub hi: f64,
    /// What `hi` left out.
    pub lo: f64,
}

impl Dd {
    /// An f64 as a double-double.
    #[inline]
    pub fn new(value: f64) -> Dd {
        Dd { hi: value, lo: 0.0 }
    }

    /// The value rounded to f64.
    #[inline]
    pub fn value(self) -> f64 {
        self.hi + self.lo
    }
}

/// a + b exactly, as the rounded sum and its rounding error (Knuth's two-sum, 6 flops).
#[inline(always)]
pub(crate) fn two_sum(a: f64, b: f64) -> Dd {
    let hi = a + b;
    let b_virtual = hi - a;
    let a_virtual = hi - b_virtual;
    let lo = (a - a_virtual) + (b - b_virtual);
    Dd { hi, lo }
}

/// a + b exactly when |a| >= |b| (or a = 0) (Dekker's fast two-sum, 3 flops).
#[inline(always)]
fn fast_two_sum(a: f64, b: f64) -> Dd {
    let hi = a + b;
    let lo = b - (hi - a);
    Dd { hi, lo }
}

/// a * b exactly, as the rounded product and its rounding error (exact unless the
/// product overflows or underflows).
#[inline(always)]
pub(crate) fn two_prod(a: f64, b: f64) -> Dd {
    let hi = a * b;
    // WebAssembly has no fused multiply-add: `mul_add` there is a software `fma` of many
    // instructions, and Dekker's split gives the same exact error in 17 flops.
    #[cfg(target_arch = "wasm32")]
    let lo = split_error(a, b, hi);
    #[cfg(not(target_arch = "wasm32"))]
    let lo = a.mul_add(b, -hi);
    Dd { hi, lo }
}

/// Veltkamp's splitter, 2^27 + 1: `x` splits into two halves of 26 bits each.
#[cfg(any(test, target_arch = "wasm32"))]
const SPLITTER: f64 = 134_217_729.0;

/// The rounding error of `hi = a * b`, `a * b - hi`, by Dekker's two-product: `a` and `b`
/// split into halves whose products are exact, summed in an order that keeps it exact.
/// That needs the splits not to overflow and the partial products not to underflow;
/// outside that range the fused multiply-add gives it. Both are exact, so the error is
/// the same bits either way.
#[cfg(any(test, target_arch = "wasm32"))]
#[inline(always)]
fn split_error(a: f64, b: f64, hi: f64) -> f64 {
    // 2^995, 2^1000 and 2^-900: the splits and the partial products stay finite, and
    // every partial product is normal.
    const LARGE: f64 = f64::from_bits(0x7e2 << 52);
    const LARGE_PRODUCT: f64 = f64::from_bits(0x7e7 << 52);
    const SMALL: f64 = f64::from_bits(0x07b << 52);
    let product = hi.abs();
    if !(a.abs() < LARGE && b.abs() < LARGE && product < LARGE_PRODUCT && product > SMALL) {
        return a.mul_add(b, -hi);
    }
    let split = |x: f64| {
        let c = SPLITTER * x;
        let high = c - (c - x);
        (high, x - high)
    };
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    ((ah * bh - hi) + ah * bl + al * bh) + al * bl
}

/// a × b + c rounded once: the fused multiply-add. In WebAssembly, which has none and
/// calls a software `fma` of many instructions for `mul_add`, it is emulated from exact
/// transformations with Boldo and Melquiond's rounding to odd ([`emulated_fma`]); the
/// same bits.
#[inline(always)]
pub(crate) fn fused(a: f64, b: f64, c: f64) -> f64 {
    #[cfg(target_arch = "wasm32")]
    return emulated_fma(a, b, c);
    #[cfg(not(target_arch = "wasm32"))]
    a.mul_add(b, c)
}

/// a × b + c rounded once, from error-free transformations (Boldo and Melquiond,
/// "Emulation of FMA and correctly rounded sums: proved algorithms using rounding to
/// odd", IEEE Trans. Computers 57, 2008): the product exactly as uh + ul, c + uh exactly
/// as th + tl, then tl + ul rounded to odd (an inexact sum whose rounding is even moves
/// to the neighbour on the other side of the exact value) and th plus that, rounded to
/// nearest. The proof wants no underflow or overflow on the way: where the product, c or
/// the result lie outside [2^-900, 2^1000] (but for zeros), the software `fma` gives it.
#[cfg(any(test, target_arch = "wasm32"))]
#[inline(always)]
fn emulated_fma(a: f64, b: f64, c: f64) -> f64 {
    // 2^1000 and 2^-900, as in `split_error`.
    const LARGE: f64 = f64::from_bits(0x7e7 << 52);
    const SMALL: f64 = f64::from_bits(0x07b << 52);
    let in_range = |x: f64| x.abs() > SMALL && x.abs() < LARGE;
    let uh = a * b;
    if (a == 0.0 || b == 0.0) && uh == 0.0 {
        // A zero product (of finite factors) is exact: one rounding of the sum.
        return uh + c;
    }
    if !(in_range(uh) && (c == 0.0 || in_range(c))) {
        return a.mul_add(b, c);
    }
    let ul = split_error(a, b, uh);
    let t = two_sum(c, uh);
    let sum = two_sum(t.lo, ul);
    let bits = sum.hi.to_bits();
    let odd = match sum.lo != 0.0 && bits & 1 == 0 {
        true if (sum.lo > 0.0) == (sum.hi > 0.0) => f64::from_bits(bits + 1),
        true => f64::from_bits(bits - 1),
        false => sum.hi,
    };
    let result = t.hi + odd;
    match result == 0.0 || in_range(result) {
        true => result,
        false => a.mul_add(b, c),
    }
}

impl Add for Dd {
    type Output = Dd;
    /// The sum, with an error of a few units in the 106th bit of the larger operand.
    #[inline(always)]
    fn add(self, other: Dd) -> Dd {
        let s = two_sum(self.hi, other.hi);
        let t = two_sum(self.lo, other.lo);
        let u = fast_two_sum(s.hi, s.lo + t.hi);
        fast_two_sum(u.hi, u.lo + t.lo)
    }
}

impl Neg for Dd {
    type Output = Dd;
    #[inline(always)]
    fn neg(self) -> Dd {
        Dd {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl Sub for Dd {
    type Output = Dd;
    #[inline(always)]
    fn sub(self, other: Dd) -> Dd {
        self + -other
    }
}

impl Mul for Dd {
    type Output = Dd;
    /// The product; the lo * lo term is below the result's precision and left out.
    #[inline(always)]
    fn mul(self, other: Dd) -> Dd {
        let p = two_prod(self.hi, other.hi);
        fast_two_sum(p.hi, p.lo + (self.hi * other.lo + self.lo * other.hi))
    }
}

impl Mul<Dd> for f64 {
    type Output = Dd;
    #[inline(always)]
    fn mul(self, other: Dd) -> Dd {
        let p = two_prod(self, other.hi);
        fast_two_sum(p.hi, p.lo + self * other.lo)
    }
}

/// u² for a pair u, as an unnormalised pair: hi² exactly by two-prod, the cross term
/// 2 hi lo in lo (lo² is below the precision).
#[inline(always)]
pub(crate) fn square(u: Dd) -> Dd {
    let p = two_prod(u.hi, u.hi);
    Dd {
        hi: p.hi,
        lo: p.lo + 2.0 * u.hi * u.lo,
    }
}

/// c u v for pairs u and v, as an unnormalised pair: c (u.hi v.hi) exactly by two
/// two-products, the cross terms c (u.hi v.lo + u.lo v.hi) in lo.
#[inline(always)]
pub(crate) fn scaled_product(c: f64, u: Dd, v: Dd) -> Dd {
    let p = two_prod(u.hi, v.hi);
    let q = two_prod(c, p.hi);
    Dd {
        hi: q.hi,
        lo: q.lo + c * (p.lo + (u.hi * v.lo + u.lo * v.hi)),
    }
}

/// c u for a pair u, as an unnormalised pair.
#[inline(always)]
pub(crate) fn scaled(c: f64, u: Dd) -> Dd {
    let q = two_prod(c, u.hi);
    Dd {
        hi: q.hi,
        lo: q.lo + c * u.lo,
    }
}

/// The sum of N pairs, rounded once (see [`sum_as_dd`]).
#[inline(always)]
pub(crate) fn sum_as_f64<const N: usize>(terms: [Dd; N]) -> f64 {
    sum_as_dd(terms).value()
}

/// The sum of N pairs as an unnormalised pair: the leading parts are added two by two as
/// a tree (each addition by two-sum, its error kept), then all the errors and low parts,
/// also as a tree. As accurate as summing in twice the precision and rounding (the Sum2
/// algorithm of Ogita, Rump and Oishi), but a chain of log2(N) additions instead of N,
/// which matters where the caller waits on the sum.
#[inline(always)]
pub(crate) fn sum_as_dd<const N: usize>(terms: [Dd; N]) -> Dd {
    let mut leading = terms.map(|term| term.hi);
    let mut errors = [0.0; N];
    let mut count = N;
    let mut found = 0;
    while count > 1 {
        let half = count / 2;
        for i in 0..half {
            let sum = two_sum(leading[2 * i], leading[2 * i + 1]);
            leading[i] = sum.hi;
            errors[found] = sum.lo;
            found += 1;
        }
        if count % 2 == 1 {
            leading[half] = leading[count - 1];
        }
        count -= half;
    }
    Dd {
        hi: leading[0],
        lo: plain_sum(terms.map(|term| term.lo)) + plain_sum(errors),
    }
}

/// An f64 sum of N numbers, added two by two as a tree.
#[inline(always)]
fn plain_sum<const N: usize>(mut values: [f64; N]) -> f64 {
    let mut count = N;
    while count > 1 {
        let half = count / 2;
        for i in 0..half {
            values[i] = values[2 * i] + values[2 * i + 1];
        }
        if count % 2 == 1 {
            values[half] = values[count - 1];
        }
        count -= half;
    }
    if N == 0 { 0.0 } else { values[0] }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_sum_and_two_prod_are_exact() {
        // 1 + 2^-60 is not an f64; the pair keeps the 2^-60.
        let s = two_sum(1.0, 2f64.powi(-60));
        assert_eq!((s.hi, s.lo), (1.0, 2f64.powi(-60)));
        // (1 + 2^-30)² = 1 + 2^-29 + 2^-60: the last term is the product's rounding error.
        let x = 1.0 + 2f64.powi(-30);
        let p = two_prod(x, x);
        assert_eq!((p.hi, p.lo), (1.0 + 2f64.powi(-29), 2f64.powi(-60)));
    }

    #[test]
    fn dekker_s_split_gives_the_fused_multiply_add_s_error() {
        // The error of a product is one number: the split (WebAssembly's two-product) and
        // the fused multiply-add (everywhere else) must give the same bits. Pairs from a
        // fixed sequence across the whole exponent range, both signs, and the edges where
        // the split hands over to the fused multiply-add.
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let mut values = vec![
            0.0,
            -0.0,
            1.0,
            1.0 + f64::EPSILON,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            f64::INFINITY,
            f64::from_bits(0x7e2 << 52),
            f64::from_bits(0x07b << 52),
            1e8 + 1.0,
            0.1,
        ];
        for _ in 0..20_000 {
            let bits = next();
            // Exponents over the whole range, biased towards the scenes' magnitudes.
            let exponent = match bits % 4 {
                0 => (next() % 2046) + 1,
                _ => 1023 - 60 + (next() % 120),
            };
            let mantissa = next() & ((1 << 52) - 1);
            let sign = (bits >> 63) << 63;
            values.push(f64::from_bits(sign | exponent << 52 | mantissa));
        }
        for pair in values.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            let hi = a * b;
            let fused = a.mul_add(b, -hi);
            let split = split_error(a, b, hi);
            assert!(
                fused.to_bits() == split.to_bits() || (fused.is_nan() && split.is_nan()),
                "{a:e} x {b:e}: fma {fused:e}, split {split:e}"
            );
        }
        assert_eq!(SPLITTER, 2f64.powi(27) + 1.0);
    }

    #[test]
    fn the_emulated_fused_multiply_add_is_the_processor_s() {
        // Against `mul_add` (the processor's FMA, or the C library's; both correctly
        // rounded) on triples from a fixed sequence: exponents across the range and near
        // the scenes', c of every size against the product, c that cancels the product to
        // the last bits, ties built from exact products, zeros and non-finite values.
        fn next(state: &mut u64) -> u64 {
            *state ^= *state << 13;
            *state ^= *state >> 7;
            *state ^= *state << 17;
            *state
        }
        fn number(state: &mut u64, wide: bool) -> f64 {
            let bits = next(state);
            let exponent = match wide {
                true => (next(state) % 2046) + 1,
                false => 1023 - 30 + (next(state) % 60),
            };
            let mantissa = next(state) & ((1 << 52) - 1);
            f64::from_bits((bits >> 63) << 63 | exponent << 52 | mantissa)
        }
        let state = &mut 0x2545_f491_4f6c_dd1d_u64;
        let mut triples = Vec::new();
        for k in 0..300_000 {
            let (a, b) = (number(state, k % 5 == 0), number(state, k % 7 == 0));
            let product = a * b;
            let small = (next(state) % 1024) as f64;
            let c = match k % 6 {
                0 => number(state, k % 11 == 0),
                1 => -product,
                2 => -product * (1.0 + f64::EPSILON * (small % 64.0)),
                3 => -product + product * f64::EPSILON * ((small % 9.0) - 4.0) / 2.0,
                4 => small * product.abs().max(1e-300) * f64::EPSILON / 4.0,
                _ => number(state, false) * (product.abs() + 1.0),
            };
            triples.push((a, b, c));
        }
        // Double rounding's own cases: a product just off 3 × 2^(k-1) (uh exactly that,
        // ul a hair below), and c on the grid of 2^k, so that c + uh falls on a midpoint
        // and only ul says which way: rounding tl + ul to nearest loses it.
        for k in [-20, 0, 1, 10, 30] {
            let (a, b) = (
                3.0 * (1.0 + 2f64.powi(-40)),
                2f64.powi(k - 1) * (1.0 - 2f64.powi(-40)),
            );
            for r in 0..6 {
                let c = (2f64.powi(52) + f64::from(r)) * 2f64.powi(k);
                triples.extend([(a, b, c), (-a, b, -c), (a, -b, -c), (-a, -b, c)]);
            }
        }
        let special = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.5,
            3.0,
            f64::INFINITY,
            f64::NAN,
            5e-324,
            1e308,
        ];
        for a in special {
            for b in special {
                for c in special {
                    triples.push((a, b, c));
                }
            }
        }
        for (a, b, c) in triples {
            let fused = a.mul_add(b, c);
            let emulated = emulated_fma(a, b, c);
            assert!(
                fused.to_bits() == emulated.to_bits() || (fused.is_nan() && emulated.is_nan()),
                "{a:e} x {b:e} + {c:e}: fma {fused:e}, emulated {emulated:e}"
            );
        }
    }

    #[test]
    fn cancellation_keeps_the_low_digits() {
        // (1e8 + 1e-9)² - 1e16 = 0.2 + 1e-18. In f64, 1e8 + 1e-9 rounds to 1e8 and the
        // difference comes out as 0; the pair gives 0.2 to the last bit.
        let x = Dd::new(1e8) + Dd::new(1e-9);
        let difference = x * x - Dd::new(1e16);
        assert!((difference.value() - 0.2).abs() <= 1e-16, "{difference:?}");
        let plain = (1e8f64 + 1e-9) * (1e8 + 1e-9) - 1e16;
        assert_eq!(plain, 0.0);
    }

    #[test]
    fn sum_terms_keeps_what_cancels() {
        // 1e16 + 1 + 1 - 1e16 = 2 exactly; in f64 each 1 is lost against 1e16 (ulp 2 there,
        // ties to even), and the plain sum is 0.
        let plain = 1e16f64 + 1.0 + 1.0 - 1e16;
        assert_eq!(plain, 0.0);
        let terms = [1e16, 1.0, 1.0, -1e16].map(Dd::new);
        assert_eq!(sum_as_f64(terms), 2.0);
        // (1e8 + 1)² - 1e16 - 2e8 = 1, with the square kept exact by two-prod.
        let x = 1e8 + 1.0;
        assert_eq!(
            sum_as_f64([two_prod(x, x), Dd::new(-1e16), Dd::new(-2e8)]),
            1.0
        );
        // 3 (1e8 + 2^-30)² - 3e16 = 6e8 2^-30 + 3 2^-60: the first term comes from the
        // cross terms alone (in f64, 1e8 + 2^-30 is 1e8 and the difference is 0); the
        // second, lo², is below the precision and left out.
        let u = two_sum(1e8, 2f64.powi(-30));
        let sum = sum_as_f64([scaled_product(3.0, u, u), Dd::new(-3e16)]);
        assert!(
            (sum - 6e8 * 2f64.powi(-30)).abs() <= 2f64.powi(-58),
            "{sum}"
        );
    }
}
