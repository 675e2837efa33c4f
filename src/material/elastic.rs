//! Isotropic linear elasticity (slab, verification; spec §6.3).

use super::{SolidModel, SolidUpdate, TangentKind};
use crate::error::{require_positive, require_range, MaterialError, ParamError};
use crate::tensor::{Matrix6, Strain6, Stress6, Tangent6};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Parameters of isotropic linear elasticity (SI).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ElasticParams {
    /// Young's modulus E (Pa). The seed's slab: 25.5e9.
    pub young: f64,
    /// Poisson's ratio ν (−). The seed's slab: 0.167.
    pub poisson: f64,
    /// Mass density ρ (kg/m³). The seed's slab: 2400.
    pub density: f64,
}

impl ElasticParams {
    /// The seed's face slab (section 2.2): E = 25.5 GPa, ν = 0.167, ρ = 2400 kg/m³.
    pub fn seed_slab() -> Self {
        ElasticParams {
            young: 25.5e9,
            poisson: 0.167,
            density: 2400.0,
        }
    }

    /// Checks E > 0, −1 < ν < 0.5, ρ ≥ 0.
    pub fn validate(&self) -> Result<(), ParamError> {
        require_positive("young", self.young)?;
        require_range("poisson", self.poisson, -0.999, 0.499_999)?;
        crate::error::require_non_negative("density", self.density)
    }
}

/// Linear elastic model: σ = σ_n + D Δε with constant D.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearElastic {
    d: Tangent6,
}

/// State of a linear elastic point: its stress.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct ElasticState {
    /// Stress (Pa, tension positive).
    pub stress: Stress6,
}

impl LinearElastic {
    /// Builds the model (parameters must have passed [`ElasticParams::validate`]).
    pub fn new(p: &ElasticParams) -> Self {
        LinearElastic {
            d: Tangent6(isotropic_stiffness(p.young, p.poisson)),
        }
    }
    /// The constant stiffness D.
    pub fn stiffness(&self) -> &Tangent6 {
        &self.d
    }
}

/// Isotropic stiffness in Voigt form with engineering shear:
///
/// ```text
/// D = λ m⊗m + 2μ I_sym,  λ = Eν/((1+ν)(1−2ν)),  μ = E/(2(1+ν));  shear diagonal entries = μ
/// ```
pub fn isotropic_stiffness(young: f64, poisson: f64) -> Matrix6 {
    let lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
    let mu = young / (2.0 * (1.0 + poisson));
    bulk_shear_stiffness(lambda + 2.0 * mu / 3.0, mu)
}

/// Stiffness from bulk modulus K and shear modulus G: D = K m⊗m + 2G (I_sym − ⅓ m⊗m) (spec eq. (R3)).
pub fn bulk_shear_stiffness(k: f64, g: f64) -> Matrix6 {
    let mut d = Matrix6::zeros();
    for i in 0..3 {
        for j in 0..3 {
            d[(i, j)] = k - 2.0 * g / 3.0;
        }
        d[(i, i)] = k + 4.0 * g / 3.0;
        d[(i + 3, i + 3)] = g;
    }
    d
}

impl SolidModel for LinearElastic {
    type State = ElasticState;
    const CONSTANT_TANGENT: bool = true;

    fn elastic_tangent(&self, _state: &ElasticState) -> Tangent6 {
        self.d
    }

    fn symmetric_tangent(&self) -> bool {
        true
    }

    fn init_state(&self, sigma0: &Stress6) -> Result<ElasticState, MaterialError> {
        Ok(ElasticState { stress: *sigma0 })
    }

    fn update(
        &self,
        prev: &ElasticState,
        d_eps: &Strain6,
    ) -> Result<SolidUpdate<ElasticState>, MaterialError> {
        let stress = Stress6(prev.stress.0 + self.d.0 * d_eps.0);
        Ok(SolidUpdate {
            state: ElasticState { stress },
            tangent: self.d,
            kind: TangentKind::Elastic,
            substeps: 1,
        })
    }

    fn stress(state: &ElasticState) -> Stress6 {
        state.stress
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tensor::Vector6;

    #[test]
    fn uniaxial_stress_recovers_young_and_poisson() {
        let (e, nu) = (25.5e9, 0.167);
        let d = isotropic_stiffness(e, nu);
        let c = d.try_inverse().expect("invertible");
        let eps = c * Vector6::new(1.0e6, 0.0, 0.0, 0.0, 0.0, 0.0);
        assert!((1.0e6 / eps[0] - e).abs() / e < 1e-12);
        assert!((-eps[1] / eps[0] - nu).abs() < 1e-12);
    }

    #[test]
    fn validation_rejects_negative_modulus() {
        let mut p = ElasticParams::seed_slab();
        p.young = -1.0;
        assert_eq!(p.validate().unwrap_err().field, "young");
    }
}
