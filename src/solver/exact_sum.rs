//! Order-independent summation: the same sum, bit for bit, whatever the order of the terms and
//! however they are spread over MPI ranks.
//!
//! Floating-point addition is not associative, so a sum split over ranks (partial sums, then an
//! `MPI_Allreduce`) changes in its last bits with the rank count. cfrd's Newton decisions (the
//! convergence test, the line search, the cut-backs) rest on such sums, and a last-bit change
//! there can send a path-dependent elasto-plastic run down another load path. Every sum that
//! feeds a decision is therefore taken exactly, on a fixed-point grid:
//!
//! ```text
//! M = max |v_i| (exact in any order),   s = 2^(K − e(M)),  e(M) the binary exponent of M,
//! S = Σ_i round(s·v_i)   in 128-bit integers (exact, associative),   result = S / s
//! ```
//! With K = 96 every |s·v_i| ≤ 2^96, so up to 2^30 terms fit in an i128. Each term is rounded to
//! the grid once (an absolute error of at most M·2^−97 ≈ 6e-30·M, far below the error of a plain
//! floating-point sum) and the integer sum and the single final rounding are independent of the
//! order. A non-finite term makes the result NaN.

/// Bits of the grid above the largest term's binary exponent.
const GRID_BITS: i32 = 96;

/// The fixed-point grid of a set of terms whose largest magnitude is `max_abs`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExactGrid {
    /// Power of two the terms are scaled by before rounding (0 when every term is zero).
    scale: f64,
}

impl ExactGrid {
    /// The grid for terms of magnitude at most `max_abs` (finite, ≥ 0).
    pub fn new(max_abs: f64) -> ExactGrid {
        if max_abs == 0.0 || !max_abs.is_finite() {
            return ExactGrid { scale: 0.0 };
        }
        // binary exponent e with 2^(e−1) ≤ max_abs < 2^e, clamped so the scale stays finite
        let e = max_abs.log2().floor() as i32 + 1;
        let k = (GRID_BITS - e).clamp(-1000, 1000);
        ExactGrid { scale: 2f64.powi(k) }
    }

    /// The exact integer sum of `values` on this grid (a partial sum; add partial sums as
    /// integers, then convert once with [`ExactGrid::to_f64`]).
    pub fn partial(&self, values: impl IntoIterator<Item = f64>) -> i128 {
        if self.scale == 0.0 {
            return 0;
        }
        values
            .into_iter()
            .map(|v| (v * self.scale).round() as i128)
            .fold(0i128, i128::wrapping_add)
    }

    /// The value of an integer sum on this grid.
    pub fn to_f64(&self, sum: i128) -> f64 {
        if self.scale == 0.0 {
            0.0
        } else {
            sum as f64 / self.scale
        }
    }
}

/// Largest magnitude of `values`, NaN if any is not finite (max is exact in any order).
pub fn max_abs(values: impl IntoIterator<Item = f64>) -> f64 {
    let mut m = 0.0f64;
    for v in values {
        if !v.is_finite() {
            return f64::NAN;
        }
        m = m.max(v.abs());
    }
    m
}

/// Serial exact sum of `values` (the single-rank case of the collective sum).
pub fn exact_sum_serial(values: &[f64]) -> f64 {
    let m = max_abs(values.iter().copied());
    if m.is_nan() {
        return f64::NAN;
    }
    let grid = ExactGrid::new(m);
    grid.to_f64(grid.partial(values.iter().copied()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Terms spanning 30 decades with both signs, in a fixed pseudo-random order.
    fn terms(n: usize) -> Vec<f64> {
        let mut x = 0x2545F4914F6CDD1Du64;
        (0..n)
            .map(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                let mant = (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
                let dec = ((x >> 3) % 30) as i32 - 15;
                mant * 10f64.powi(dec)
            })
            .collect()
    }

    #[test]
    fn the_sum_does_not_depend_on_order_or_split() {
        let v = terms(10_000);
        let reference = exact_sum_serial(&v);
        let mut rev = v.clone();
        rev.reverse();
        assert_eq!(exact_sum_serial(&rev).to_bits(), reference.to_bits());
        // a split into "ranks": partial integer sums on the common grid
        let grid = ExactGrid::new(max_abs(v.iter().copied()));
        for parts in [2usize, 3, 7] {
            let chunk = v.len().div_ceil(parts);
            let total = v
                .chunks(chunk)
                .map(|c| grid.partial(c.iter().copied()))
                .fold(0i128, i128::wrapping_add);
            assert_eq!(grid.to_f64(total).to_bits(), reference.to_bits(), "{parts} parts");
        }
        // a plain floating-point sum does depend on the order for these terms
        let fwd: f64 = v.iter().sum();
        let bwd: f64 = rev.iter().sum();
        assert_ne!(fwd.to_bits(), bwd.to_bits());
    }

    #[test]
    fn the_sum_is_accurate() {
        let v = terms(10_000);
        let m = max_abs(v.iter().copied());
        // compensated (Neumaier) sum as the reference
        let (mut s, mut c) = (0.0f64, 0.0f64);
        for &x in &v {
            let t = s + x;
            c += if s.abs() >= x.abs() {
                (s - t) + x
            } else {
                (x - t) + s
            };
            s = t;
        }
        let err = (exact_sum_serial(&v) - (s + c)).abs();
        assert!(err <= 1e-15 * m, "error {err:e} for largest term {m:e}");
        assert_eq!(exact_sum_serial(&[1.0, 2.0, 3.5]), 6.5);
        assert_eq!(exact_sum_serial(&[]), 0.0);
        assert_eq!(exact_sum_serial(&[0.0, -0.0]), 0.0);
        assert!(exact_sum_serial(&[1.0, f64::NAN]).is_nan());
        assert!(exact_sum_serial(&[1.0, f64::INFINITY]).is_nan());
        assert_eq!(exact_sum_serial(&[1e300, -1e300, 1e-300]), 0.0);
    }
}
