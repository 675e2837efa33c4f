//! Minimal mixed-control material-point driver for solid models (spec §9: stress-controlled
//! components are Newton-iterated with the model's tangent to 10⁻⁸ relative).
//!
//! Generic over [`SolidModel`]; used by the point runner for the triaxial and oedometer tests.
//! It is deliberately small: when the project's full solid driver (`material::driver_solid`)
//! lands, [`run_solid_path`] is the one function to point at it.

use crate::error::MaterialError;
use crate::material::SolidModel;
use crate::tensor::{Strain6, Stress6, Vector6};
use nalgebra::{DMatrix, DVector};

/// Relative tolerance of the stress-controlled components.
const STRESS_TOL: f64 = 1e-8;
/// Largest number of Newton iterations per step.
const MAX_ITER: usize = 50;

/// Control of one Voigt component in one step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Control {
    /// Prescribed strain increment (engineering shear for indices 3..6).
    Strain(f64),
    /// Prescribed total stress at the end of the step (Pa, tension positive).
    Stress(f64),
}

/// One output row.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolidRow {
    /// Step number (0 = initial state).
    pub step: usize,
    /// Total strain since the start (Voigt, engineering shear, tension positive).
    pub strain: [f64; 6],
    /// Stress (Pa, Voigt, tension positive).
    pub stress: [f64; 6],
}

/// Runs a mixed-control path from the state `model.init_state(sigma0)`.
pub fn run_solid_path<M: SolidModel>(
    model: &M,
    sigma0: &Stress6,
    steps: &[[Control; 6]],
) -> Result<Vec<SolidRow>, (usize, MaterialError)> {
    let mut state = model.init_state(sigma0).map_err(|e| (0, e))?;
    let mut strain = Vector6::zeros();
    let mut rows = vec![SolidRow {
        step: 0,
        strain: [0.0; 6],
        stress: M::stress(&state).0.into(),
    }];
    for (k, ctl) in steps.iter().enumerate() {
        let step = k + 1;
        let free: Vec<usize> = (0..6).filter(|&i| matches!(ctl[i], Control::Stress(_))).collect();
        let mut d_eps = Vector6::zeros();
        for i in 0..6 {
            if let Control::Strain(v) = ctl[i] {
                d_eps[i] = v;
            }
        }
        let mut up = model.update(&state, &Strain6(d_eps)).map_err(|e| (step, e))?;
        for iter in 0..=MAX_ITER {
            let sig = M::stress(&up.state).0;
            let residual = DVector::from_iterator(
                free.len(),
                free.iter().map(|&i| match ctl[i] {
                    Control::Stress(target) => sig[i] - target,
                    Control::Strain(_) => 0.0,
                }),
            );
            let scale = sig.norm().max(1.0);
            if residual.amax() <= STRESS_TOL * scale {
                break;
            }
            if iter == MAX_ITER {
                return Err((
                    step,
                    MaterialError::new(format!(
                        "mixed control did not converge (residual {:.3e} Pa)",
                        residual.amax()
                    )),
                ));
            }
            let d = &up.tangent.0;
            let jac = DMatrix::from_fn(free.len(), free.len(), |a, b| d[(free[a], free[b])]);
            let corr = jac.lu().solve(&residual).ok_or_else(|| {
                (
                    step,
                    MaterialError::new("singular tangent in the stress-controlled block"),
                )
            })?;
            for (a, &i) in free.iter().enumerate() {
                d_eps[i] -= corr[a];
            }
            up = model.update(&state, &Strain6(d_eps)).map_err(|e| (step, e))?;
        }
        strain += d_eps;
        state = up.state;
        rows.push(SolidRow {
            step,
            strain: strain.into(),
            stress: M::stress(&state).0.into(),
        });
    }
    Ok(rows)
}

/// Steps of a drained triaxial compression: axial (z) compression strain increments, lateral
/// stresses held at −σ_3, no shear strain.
pub fn triaxial_steps(confining: f64, axial_compression_increments: &[f64]) -> Vec<[Control; 6]> {
    axial_compression_increments
        .iter()
        .map(|&de| {
            [
                Control::Stress(-confining),
                Control::Stress(-confining),
                Control::Strain(-de),
                Control::Strain(0.0),
                Control::Strain(0.0),
                Control::Strain(0.0),
            ]
        })
        .collect()
}

/// Steps of an oedometric compression: axial (z) compression strain increments, no other strain.
pub fn oedometer_steps(axial_compression_increments: &[f64]) -> Vec<[Control; 6]> {
    axial_compression_increments
        .iter()
        .map(|&de| {
            let mut c = [Control::Strain(0.0); 6];
            c[2] = Control::Strain(-de);
            c
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::elastic::{ElasticParams, LinearElastic};

    /// Elastic triaxial: q/ε_a = E and ε_v/ε_a = 1 − 2ν (compression positive) to 1e-9.
    #[test]
    fn elastic_triaxial_recovers_young_and_poisson() {
        let p = ElasticParams {
            young: 50e6,
            poisson: 0.3,
            density: 2000.0,
        };
        let m = LinearElastic::new(&p);
        let rows = run_solid_path(
            &m,
            &Stress6::isotropic(-200e3),
            &triaxial_steps(200e3, &[1e-4; 20]),
        )
        .unwrap();
        let r = rows.last().unwrap();
        let eps_a = -r.strain[2];
        let q = r.stress[0] - r.stress[2];
        assert!((q / eps_a - 50e6).abs() < 1e-6 * 50e6, "E = {}", q / eps_a);
        let eps_v = -(r.strain[0] + r.strain[1] + r.strain[2]);
        assert!((eps_v / eps_a - 0.4).abs() < 1e-9, "{}", eps_v / eps_a);
        assert!((r.stress[0] + 200e3).abs() < 1e-3);
    }
}
