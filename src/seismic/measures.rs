//! Ground-motion measures of a record (spec seismic §2.3): velocity and displacement by
//! integration, peak values, end values, pairwise correlation of components, and the
//! spectral match against a target.

/// Velocity and displacement of a piecewise-linear acceleration from rest: the exact
/// integrals, v_{i+1} = v_i + dt·(a_i + a_{i+1})/2, d_{i+1} = d_i + dt·v_i + dt²·(2a_i + a_{i+1})/6.
pub fn integrate(accel: &[f64], dt: f64) -> (Vec<f64>, Vec<f64>) {
    let mut v = Vec::with_capacity(accel.len());
    let mut d = Vec::with_capacity(accel.len());
    let (mut vi, mut di) = (0.0, 0.0);
    v.push(vi);
    d.push(di);
    for w in accel.windows(2) {
        di += dt * vi + dt * dt * (2.0 * w[0] + w[1]) / 6.0;
        vi += 0.5 * dt * (w[0] + w[1]);
        v.push(vi);
        d.push(di);
    }
    (v, d)
}

/// Largest absolute value (0 for an empty slice).
pub fn peak_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |m: f64, v| m.max(v.abs()))
}

/// Peak and end values of one component (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotionMeasures {
    /// Peak ground acceleration (m/s²).
    pub pga: f64,
    /// Peak ground velocity (m/s).
    pub pgv: f64,
    /// Peak ground displacement (m).
    pub pgd: f64,
    /// Velocity at the end of the record (m/s).
    pub end_velocity: f64,
    /// Displacement at the end of the record (m).
    pub end_displacement: f64,
}

impl MotionMeasures {
    /// The measures of a record component sampled at `dt`.
    pub fn of(accel: &[f64], dt: f64) -> Self {
        let (v, d) = integrate(accel, dt);
        MotionMeasures {
            pga: peak_abs(accel),
            pgv: peak_abs(&v),
            pgd: peak_abs(&d),
            end_velocity: v.last().copied().unwrap_or(0.0),
            end_displacement: d.last().copied().unwrap_or(0.0),
        }
    }
}

/// Pearson correlation coefficient of two equally long series (0 when one is constant).
pub fn correlation(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len()) as f64;
    let mean = |x: &[f64]| x.iter().sum::<f64>() / n;
    let (ma, mb) = (mean(a), mean(b));
    let (mut sab, mut saa, mut sbb) = (0.0, 0.0, 0.0);
    for (x, y) in a.iter().zip(b) {
        let (dx, dy) = (x - ma, y - mb);
        sab += dx * dy;
        saa += dx * dx;
        sbb += dy * dy;
    }
    if saa == 0.0 || sbb == 0.0 {
        0.0
    } else {
        sab / (saa * sbb).sqrt()
    }
}

/// A response spectrum against its target at the same periods (spec seismic §2.3).
#[derive(Debug, Clone, PartialEq)]
pub struct SpectralMatch {
    /// Periods (s).
    pub periods: Vec<f64>,
    /// Target Sa (m/s²).
    pub target: Vec<f64>,
    /// Achieved Sa (m/s²).
    pub achieved: Vec<f64>,
}

impl SpectralMatch {
    /// Ratios achieved/target.
    pub fn ratios(&self) -> Vec<f64> {
        self.achieved
            .iter()
            .zip(&self.target)
            .map(|(a, t)| a / t)
            .collect()
    }

    /// Mean of |ratio − 1|.
    pub fn mean_abs_error(&self) -> f64 {
        let r = self.ratios();
        r.iter().map(|x| (x - 1.0).abs()).sum::<f64>() / r.len().max(1) as f64
    }

    /// Largest |ratio − 1|.
    pub fn max_abs_error(&self) -> f64 {
        self.ratios().iter().fold(0.0, |m: f64, x| m.max((x - 1.0).abs()))
    }

    /// Smallest and largest ratio − 1 (signed), e.g. (−0.055, +0.096).
    pub fn error_range(&self) -> (f64, f64) {
        self.ratios()
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x - 1.0), hi.max(x - 1.0))
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Integration is exact for a constant acceleration.
    #[test]
    fn integrates_a_constant_exactly() {
        let a = vec![2.0; 11];
        let (v, d) = integrate(&a, 0.1);
        assert!(
            (v[10] - 2.0).abs() < 1e-14 && (d[10] - 1.0).abs() < 1e-14,
            "{} {}",
            v[10],
            d[10]
        );
        let m = MotionMeasures::of(&a, 0.1);
        assert!(m.pga == 2.0 && (m.pgd - 1.0).abs() < 1e-14);
    }

    #[test]
    fn correlation_of_related_series() {
        let a: Vec<f64> = (0..100).map(|i| (i as f64 * 0.3).sin()).collect();
        let b: Vec<f64> = a.iter().map(|x| -2.0 * x + 1.0).collect();
        assert!((correlation(&a, &b) + 1.0).abs() < 1e-12);
        assert_eq!(correlation(&a, &[1.0; 100]), 0.0);
    }

    #[test]
    fn spectral_errors() {
        let m = SpectralMatch {
            periods: vec![0.1, 1.0],
            target: vec![2.0, 1.0],
            achieved: vec![2.2, 0.95],
        };
        assert!((m.max_abs_error() - 0.1).abs() < 1e-12);
        assert!((m.mean_abs_error() - 0.075).abs() < 1e-12);
        let (lo, hi) = m.error_range();
        assert!((lo + 0.05).abs() < 1e-12 && (hi - 0.1).abs() < 1e-12);
    }
}
