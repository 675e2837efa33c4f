//! Assembly of the internal force f_int and the tangent K_t of the placed elements
//! (spec models §8.1: every evaluation integrates from the committed states).

use super::error::SolveError;
use super::model::{add_owned_rows, BlockStates, Model};
use super::solid::Vector24;
use crate::linalg::petsc::Vector;
use crate::parallel::{exact_sum, sum_u64};

impl Model<'_> {
    /// Updates the trial states for the current `u` and assembles f_int and (with `want_k`)
    /// K_t; with `trial_is_current` the solid trial states are known to be those of the
    /// current `u` (the last evaluation was there), so f_int and K of the solid elements come
    /// from them and their stored tangents without a second integration (the same values,
    /// since an update is a pure function of the committed state and the increment).
    /// Collective: the element loop stops at the first local failure, but the assembly calls
    /// run on every rank whatever happened.
    pub(super) fn assemble(
        &mut self,
        f_int: &mut Vector,
        want_k: bool,
        trial_is_current: bool,
    ) -> Result<(), SolveError> {
        let u_loc: Vec<f64> = self.local_u()?;
        let u0_loc: Vec<f64> = self
            .gather_committed
            .gather(&self.u_committed)?
            .read(|s| s.to_vec())?;
        f_int.set_all(0.0)?;
        if want_k {
            self.k.zero()?;
        }
        // stiffness diagonals of the owned elements, for the Dirichlet scaling (an exact sum:
        // the same at any rank count)
        let mut diagonals: Vec<f64> = Vec::new();
        let mut local = Ok(());
        let started = std::time::Instant::now();
        for i in 0..self.disc.elements.len() {
            let (b, _) = self.elem_block[i];
            if !self.active_block[b] {
                continue;
            }
            if let Err(e) = self.assemble_element(
                i,
                &u_loc,
                &u0_loc,
                f_int,
                want_k,
                trial_is_current,
                &mut diagonals,
            ) {
                if matches!(e, SolveError::Petsc(_)) {
                    return Err(e);
                }
                local = Err(e);
                break;
            }
        }
        self.element_seconds += started.elapsed().as_secs_f64();
        f_int.assemble()?;
        if want_k {
            self.k.assemble()?;
            let n = sum_u64(self.comm, diagonals.len() as u64);
            let s = exact_sum(self.comm, diagonals.iter().copied());
            self.dirichlet_diag = if n > 0 && s > 0.0 { s / n as f64 } else { 1.0 };
        }
        local
    }

    /// Evaluates the `i`-th element of this rank at the increment `u_loc − u0_loc` and adds its
    /// owned rows to f_int (and K_t with `want_k`); the absolute diagonal of K_e of an owned
    /// element goes to `diagonals`.
    fn assemble_element(
        &mut self,
        i: usize,
        u_loc: &[f64],
        u0_loc: &[f64],
        f_int: &mut Vector,
        want_k: bool,
        trial_is_current: bool,
        diagonals: &mut Vec<f64>,
    ) -> Result<(), SolveError> {
        let mesh = &self.scene.mesh;
        let e = self.disc.elements[i] as usize;
        let (b, be) = self.elem_block[i];
        let loc = &self.disc.element_local[i];
        let mut rows = [0i32; 24];
        let mut d_u = Vector24::zeros();
        for a in 0..8 {
            for c in 0..3 {
                let l = 3 * loc[a] as usize + c;
                d_u[3 * a + c] = u_loc[l] - u0_loc[l];
                rows[3 * a + c] = self.disc.local_dofs[l];
            }
        }
        let evaluated = match &mut self.blocks[b] {
            BlockStates::Solid(block) => {
                let geo = self.solid_geo[i]
                    .as_ref()
                    .expect("solid geometry built at set-up");
                if trial_is_current {
                    let r = block.evaluate_trial(be, geo);
                    Ok((r.f_int, r.k.filter(|_| want_k)))
                } else {
                    block.evaluate(be, geo, &d_u, want_k).map(|r| (r.f_int, r.k))
                }
            }
            BlockStates::Interface(block) => {
                let geo = self.iface_geo[i]
                    .as_ref()
                    .expect("interface geometry built at set-up");
                block.evaluate(be, geo, &d_u, want_k).map(|r| (r.f_int, r.k))
            }
        };
        let (fe, ke) = evaluated.map_err(|m| SolveError::Material {
            element: mesh.elements[e].id,
            reason: format!("{}: {}", element_place(mesh, e), m.reason),
        })?;
        add_owned_rows(&self.disc, f_int, &rows, fe.as_slice())?;
        let Some(ke) = ke else {
            return Ok(());
        };
        if self.disc.element_owned[i] {
            diagonals.extend(ke.diagonal().iter().map(|v| v.abs()));
        }
        // the owned rows, row-major (nalgebra is column-major)
        let mut kt = [0.0f64; 576];
        let mut owned_rows = [0i32; 24];
        let mut m = 0;
        for (r, &d) in rows.iter().enumerate() {
            if self.disc.owns_dof(d) {
                owned_rows[m] = d;
                for c in 0..24 {
                    kt[24 * m + c] = ke[(r, c)];
                }
                m += 1;
            }
        }
        if m > 0 {
            self.k.add_values(&owned_rows[..m], &rows, &kt[..24 * m])?;
        }
        Ok(())
    }
}

/// Where element `e` of `mesh` is, for messages: "block 'NAME' at (x, y, z)" with the centroid
/// of its nodes in m.
fn element_place(mesh: &crate::mesh::Mesh, e: usize) -> String {
    let el = &mesh.elements[e];
    let mut c = [0.0f64; 3];
    for &n in &el.nodes {
        for (k, ck) in c.iter_mut().enumerate() {
            *ck += mesh.coords[n as usize][k] / 8.0;
        }
    }
    format!(
        "block '{}' at ({:.2}, {:.2}, {:.2})",
        mesh.blocks[el.block as usize].name, c[0], c[1], c[2]
    )
}
