//! Output steps: their metadata, the records of what was written, component labels.

use crate::io::xdmf::Center;
use crate::tensor::Strain6;

/// Metadata of one output step.
#[derive(Debug, Clone, PartialEq)]
pub struct StepInfo {
    /// Time (s) of a dynamic step, or the pseudo-time (load factor) of a static stage; shown by
    /// ParaView, so it should increase from step to step.
    pub time: f64,
    /// Name of the stage (e.g. `impoundment`).
    pub stage: String,
    /// Free label (e.g. `increment 3/10`).
    pub label: String,
}

/// A field written in a step.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldRecord {
    /// Field name (the dataset's name in the step group).
    pub name: String,
    /// Node or element field.
    pub center: Center,
    /// Components per row.
    pub ncomp: usize,
    /// Absolute dataset path.
    pub dataset: String,
}

/// A step written to the file.
#[derive(Debug, Clone, PartialEq)]
pub struct StepRecord {
    /// Step number, 1-based, in writing order.
    pub number: u64,
    /// Absolute group path, e.g. `/steps/000001`.
    pub group: String,
    /// The step's metadata.
    pub info: StepInfo,
    /// Fields written so far.
    pub fields: Vec<FieldRecord>,
}

/// Component labels stored in a field's `components` attribute.
pub fn component_labels(ncomp: usize) -> String {
    match ncomp {
        1 => "value".to_string(),
        3 => "x,y,z".to_string(),
        6 => "xx,yy,zz,xy,yz,zx".to_string(),
        n => (0..n).map(|i| format!("c{i}")).collect::<Vec<_>>().join(","),
    }
}

/// Strain as written to results files: Voigt order with **tensor** shear components
/// ε_xy = γ_xy / 2, so that ParaView's tensor filters (eigenvalues, invariants) are right.
pub fn strain_output_components(strain: &Strain6) -> [f64; 6] {
    let v = &strain.0;
    [v[0], v[1], v[2], 0.5 * v[3], 0.5 * v[4], 0.5 * v[5]]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn component_labels_follow_the_voigt_order() {
        assert_eq!(component_labels(6), "xx,yy,zz,xy,yz,zx");
        assert_eq!(component_labels(3), "x,y,z");
        assert_eq!(component_labels(1), "value");
        assert_eq!(component_labels(2), "c0,c1");
    }

    #[test]
    fn strain_output_halves_the_engineering_shear() {
        let e = Strain6(crate::tensor::Vector6::from_column_slice(&[
            1.0, 2.0, 3.0, 4.0, 6.0, 8.0,
        ]));
        assert_eq!(strain_output_components(&e), [1.0, 2.0, 3.0, 2.0, 3.0, 4.0]);
    }
}
