//! Exact sums of non-negative doubles: each term is added as an integer multiple of the smallest
//! subnormal into 32-bit digits held in `i64`s, so a sum does not depend on the order of its
//! terms, and sums of several ranks combine by an integer `MPI_SUM` (also exact). The stopping
//! test of a distributed run reads the same bits for any number of ranks and any partition.

use crate::comm::{Comm, Op};
use fc3d::CResult;

/// 32-bit digits from 2^-1074 up to past 2^1024 (the largest double times 2^64 terms).
pub const DIGITS: usize = 68;

/// An exact sum of non-negative doubles (a non-finite term makes the sum infinite).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ExactSum {
    digits: [i64; DIGITS],
    /// Terms added since the digits were last normalised (each adds < 2^32 to a digit).
    pending: u32,
    non_finite: bool,
}

impl Default for ExactSum {
    fn default() -> Self {
        ExactSum {
            digits: [0; DIGITS],
            pending: 0,
            non_finite: false,
        }
    }
}

/// Words of one sum on the wire: its normalised digits and the non-finite flag.
pub const WORDS: usize = DIGITS + 1;

impl ExactSum {
    /// Adds `x >= 0` (a negative term is taken by its magnitude: the sums here are of squares).
    #[inline]
    pub fn add(&mut self, x: f64) {
        if !x.is_finite() {
            self.non_finite = true;
            return;
        }
        let bits = x.abs().to_bits();
        if bits == 0 {
            return;
        }
        let exponent = (bits >> 52) as usize;
        let fraction = bits & ((1 << 52) - 1);
        // x = mantissa * 2^(shift - 1074)
        let (mantissa, shift) = if exponent == 0 {
            (fraction, 0)
        } else {
            (fraction | (1 << 52), exponent - 1)
        };
        let wide = u128::from(mantissa) << (shift % 32);
        let d = shift / 32;
        self.digits[d] += (wide & 0xffff_ffff) as i64;
        self.digits[d + 1] += ((wide >> 32) & 0xffff_ffff) as i64;
        self.digits[d + 2] += (wide >> 64) as i64;
        self.pending += 1;
        if self.pending >= 1 << 30 {
            self.normalise();
        }
    }

    /// Carries so that every digit is in `0..2^32`.
    fn normalise(&mut self) {
        for k in 0..DIGITS - 1 {
            let carry = self.digits[k] >> 32;
            self.digits[k] &= 0xffff_ffff;
            self.digits[k + 1] += carry;
        }
        self.pending = 0;
    }

    /// Appends the sum's [`WORDS`] words to `out` (normalised: a reduction of up to 2^31 ranks
    /// cannot overflow a digit).
    pub fn write(&mut self, out: &mut Vec<i64>) {
        self.normalise();
        out.extend_from_slice(&self.digits);
        out.push(i64::from(self.non_finite));
    }

    /// The sum of `words` (one [`ExactSum::write`] reduced over ranks).
    pub fn read(words: &[i64]) -> Self {
        let mut s = ExactSum::default();
        s.digits.copy_from_slice(&words[..DIGITS]);
        s.non_finite = words[DIGITS] != 0;
        s.normalise();
        s
    }

    /// The sum, rounded to the nearest double.
    pub fn value(&self) -> f64 {
        if self.non_finite {
            return f64::INFINITY;
        }
        let mut s = self.clone();
        s.normalise();
        let Some(top) = (0..DIGITS).rev().find(|&k| s.digits[k] != 0) else {
            return 0.0;
        };
        let digit = |k: usize| u128::from(s.digits[k] as u64);
        let low = top.saturating_sub(2);
        let mut head = 0u128;
        for k in (low..=top).rev() {
            head = (head << 32) | digit(k);
        }
        if s.digits[..low].iter().any(|&d| d != 0) {
            // Sticky bit: far below the 53 bits kept, it only breaks ties correctly.
            head |= 1;
        }
        scale_by_power_of_two(head as f64, 32 * low as i32 - 1074)
    }

    /// Sums over the ranks of `comm` (collective), each rank's `sums` in place.
    pub fn reduce_all(comm: &Comm, sums: &mut [ExactSum], flags: &mut [i64]) -> CResult<()> {
        let mut words = Vec::with_capacity(sums.len() * WORDS + flags.len());
        for s in sums.iter_mut() {
            s.write(&mut words);
        }
        words.extend_from_slice(flags);
        comm.allreduce(&mut words, Op::Sum)?;
        for (k, s) in sums.iter_mut().enumerate() {
            *s = ExactSum::read(&words[k * WORDS..(k + 1) * WORDS]);
        }
        flags.copy_from_slice(&words[sums.len() * WORDS..]);
        Ok(())
    }
}

/// `x * 2^e` by exact powers of two (a result in the subnormal range may round twice; it is
/// the same on every rank).
fn scale_by_power_of_two(mut x: f64, mut e: i32) -> f64 {
    let power = |k: i32| f64::from_bits(((k + 1023) as u64) << 52);
    while e > 1000 {
        x *= power(1000);
        e -= 1000;
    }
    while e < -1000 {
        x *= power(-1000);
        e += 1000;
    }
    x * power(e)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sum_of(v: &[f64]) -> f64 {
        let mut s = ExactSum::default();
        v.iter().for_each(|&x| s.add(x));
        s.value()
    }

    #[test]
    fn exact_values_and_order_independence() {
        assert_eq!(sum_of(&[]), 0.0);
        assert_eq!(sum_of(&[1.5, 2.25]), 3.75);
        assert_eq!(sum_of(&[f64::MIN_POSITIVE / 8.0]), f64::MIN_POSITIVE / 8.0);
        assert_eq!(sum_of(&[f64::MAX]), f64::MAX);
        assert_eq!(sum_of(&[f64::MAX, f64::MAX]), f64::INFINITY);
        assert_eq!(sum_of(&[1.0, f64::NAN]), f64::INFINITY);
        // 1 + 2^-60 + 2^-60 ... : rounding each step would lose every small term.
        let mut v = vec![1.0];
        v.extend(std::iter::repeat_n(2f64.powi(-60), 1 << 12));
        assert_eq!(sum_of(&v), 1.0 + 2f64.powi(-48));
        let mut w = v.clone();
        w.reverse();
        assert_eq!(sum_of(&w).to_bits(), sum_of(&v).to_bits());
        // Pseudo-random terms over a wide range, summed in two orders and as two halves.
        let mut x = 0x1234_5678_9abc_def0u64;
        let terms: Vec<f64> = (0..10_000)
            .map(|_| {
                x = x
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let mantissa = 1.0 + (x >> 11) as f64 / (1u64 << 53) as f64;
                mantissa * 2f64.powi((x % 200) as i32 - 100)
            })
            .collect();
        let forward = sum_of(&terms);
        let mut rev = terms.clone();
        rev.reverse();
        assert_eq!(forward.to_bits(), sum_of(&rev).to_bits());
        let (mut a, mut b) = (ExactSum::default(), ExactSum::default());
        terms[..5000].iter().for_each(|&t| a.add(t));
        terms[5000..].iter().for_each(|&t| b.add(t));
        let (mut wa, mut wb) = (Vec::new(), Vec::new());
        a.write(&mut wa);
        b.write(&mut wb);
        let words: Vec<i64> = wa.iter().zip(&wb).map(|(x, y)| x + y).collect();
        assert_eq!(ExactSum::read(&words).value().to_bits(), forward.to_bits());
        // Close to the naive sum.
        let naive: f64 = terms.iter().sum();
        assert!((forward - naive).abs() <= 1e-12 * naive);
    }
}
