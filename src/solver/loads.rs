//! External forces of a stage: its terms (gravity, pressure, hydrostatic water) on the placed
//! elements, ramped from the previous stage's loads, and the placement forces.
//!
//! ```text
//! f_ext(λ) = f_prev + λ·(f_stage − f_prev) + f₀
//! ```

use super::error::SolveError;
use super::model::{add_owned_rows, BlockStates, Model};
use super::solid::Vector24;
use crate::element::hex8::{face_pressure_load, gravity_load, Hex8Geometry};
use crate::linalg::petsc::Vector;
use crate::scene::Term;

/// The loads carried from stage to stage.
pub struct Loads {
    /// External force at the end of the previous stage.
    pub(super) f_prev: Vector,
}

impl Loads {
    /// No loads yet (zero f_prev), laid out like `like`.
    pub(super) fn new(like: &Vector) -> Result<Self, SolveError> {
        let mut f_prev = like.duplicate()?;
        f_prev.set_all(0.0)?;
        Ok(Loads { f_prev })
    }

    /// External force of stage `terms` at load factor `lambda` (without f₀):
    /// f = f_prev + λ (f_stage − f_prev), with f_stage the terms on the placed elements.
    pub(super) fn external_force(
        &self,
        model: &Model,
        terms: &[Term],
        lambda: f64,
        f: &mut Vector,
    ) -> Result<(), SolveError> {
        f.set_all(0.0)?;
        // placed elements this rank evaluates; terms add to owned rows only, in the scene's
        // fixed order (rank-count independent, see `discretization`)
        let mesh = &model.scene.mesh;
        let mut placed = vec![false; mesh.elements.len()];
        for &e in &model.disc.elements {
            placed[e as usize] = model.active_block[mesh.elements[e as usize].block as usize];
        }
        for term in terms {
            add_term(model, term, &placed, f)?;
        }
        f.assemble()?;
        // f ← λ f_stage + (1 − λ) f_prev
        f.write(|s| s.iter_mut().for_each(|v| *v *= lambda))?;
        f.axpy(1.0 - lambda, &self.f_prev)?;
        Ok(())
    }

    /// Ends a stage: its full loads become the next stage's f_prev.
    pub(super) fn end_stage(&mut self, model: &Model, terms: &[Term]) -> Result<(), SolveError> {
        let mut f = model.u.duplicate()?;
        self.external_force(model, terms, 1.0, &mut f)?;
        self.f_prev.copy_from(&f)?;
        Ok(())
    }
}

/// Adds one term's forces on the placed elements (`placed`, by input index) to `f`.
fn add_term(model: &Model, term: &Term, placed: &[bool], f: &mut Vector) -> Result<(), SolveError> {
    let mesh = &model.scene.mesh;
    let add = |e: usize, fe: &Vector24, f: &mut Vector| -> Result<(), SolveError> {
        add_owned_rows(&model.disc, f, &model.element_dofs(e), fe.as_slice())
    };
    match term {
        Term::Gravity { g } => {
            for &e in &model.disc.elements {
                let e = e as usize;
                if !placed[e] || mesh.is_interface(e) {
                    continue;
                }
                let rho = model.scene.block_materials[mesh.elements[e].block as usize].density();
                add(e, &gravity_load(&mesh.element_coords(e), rho, g), f)?;
            }
        }
        Term::Pressure { faces, value } => {
            for face in &mesh.face_sets[faces] {
                if placed[face.element as usize] {
                    let e = face.element as usize;
                    let fe =
                        face_pressure_load(&mesh.element_coords(e), face.local_face as usize, &[*value; 4]);
                    add(e, &fe, f)?;
                }
            }
        }
        Term::Hydrostatic {
            faces,
            level,
            unit_weight,
        } => {
            for face in &mesh.face_sets[faces] {
                if placed[face.element as usize] {
                    let e = face.element as usize;
                    let p = face
                        .nodes
                        .map(|n| unit_weight * (level - mesh.coords[n as usize][2]).max(0.0));
                    let fe = face_pressure_load(&mesh.element_coords(e), face.local_face as usize, &p);
                    add(e, &fe, f)?;
                }
            }
        }
    }
    Ok(())
}

/// Adds to `f` the forces f₀ = ∫ Bᵀσ₀ dV of the placement stress σ₀ of every placed solid
/// element (spec models §8.6 item 1: a rockfill point is placed at p_min·I, not at zero stress).
///
/// σ₀ is uniform, so f₀ vanishes inside a lift and is a pressure p_min on its free faces.
/// Without f₀ that pressure is unbalanced: the faces of every new lift expand to shed it,
/// the points at the crest edges drop to p ≈ p_min/3, next to the tension cut-off
/// p_t = 0.2·p_min, and Newton chatters as they cross it and are reset to p_min·I.
/// With f₀ a lift is in equilibrium at σ₀ before its own weight acts, and the stress change
/// Δσ = σ − σ₀ balances the real loads alone.
pub(super) fn add_placement_force(model: &Model, f: &mut Vector) -> Result<(), SolveError> {
    let mesh = &model.scene.mesh;
    let mut f0 = f.duplicate()?;
    f0.set_all(0.0)?;
    for (i, &e) in model.disc.elements.iter().enumerate() {
        let (b, _) = model.elem_block[i];
        let BlockStates::Solid(block) = &model.blocks[b] else {
            continue;
        };
        if !model.active_block[b] {
            continue;
        }
        let e = e as usize;
        let geo = Hex8Geometry::new(&mesh.element_coords(e)).map_err(|_| SolveError::Geometry {
            element: mesh.elements[e].id,
        })?;
        add_owned_rows(
            &model.disc,
            &mut f0,
            &model.element_dofs(e),
            block.placement_force(&geo).as_slice(),
        )?;
    }
    f0.assemble()?;
    f.axpy(1.0, &f0)?;
    Ok(())
}
