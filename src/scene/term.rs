//! Physics terms: what the scene switches on. The assembly iterates the list; a term that is
//! not in it is never built (`spec/style.md` G.5).

/// One physics term of the residual `r = f_ext − f_int`.
#[derive(Debug, Clone, PartialEq)]
pub enum Term {
    /// Body force ρ·g on every solid element.
    Gravity {
        /// Gravity vector (m/s²).
        g: [f64; 3],
    },
    /// Uniform pressure on a face set (Pa, positive pushes against the face).
    Pressure {
        /// Face set name.
        faces: String,
        /// Pressure (Pa).
        value: f64,
    },
    /// Hydrostatic pressure γ_w·⟨level − z⟩ on a face set.
    Hydrostatic {
        /// Face set name.
        faces: String,
        /// Free-surface elevation (m).
        level: f64,
        /// γ_w (N/m³).
        unit_weight: f64,
    },
}
