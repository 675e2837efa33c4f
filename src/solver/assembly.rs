//! Assembly of the internal force f_int and the tangent K_t of the placed elements
//! (spec models §8.1: every evaluation integrates from the committed states).

use super::error::SolveError;
use super::model::{BlockStates, Model};
use super::solid::{Matrix24, Vector24};
use super::tangent_slots::TangentSlots;
use crate::element::hex8::Hex8Geometry;
use crate::element::interface8::Interface8Geometry;
use crate::linalg::petsc::Vector;
use crate::parallel::{exact_sum, sum_u64};

impl Model<'_> {
    /// Updates the trial states for the current `u` and assembles f_int and (with `want_k`)
    /// K_t; with `trial_is_current` the trial states are known to be those of the current
    /// `u` (the last evaluation was there), so f_int and K of the solid and interface elements
    /// come from them and their stored tangents without a second integration (the same values,
    /// since an update is a pure function of the committed state and the increment).
    /// The sums go straight into the owned entries of f_int and K ([`TangentSlots`]).
    /// Collective: the element loop stops at the first local failure, but the assembly calls
    /// run on every rank whatever happened.
    pub(super) fn assemble(
        &mut self,
        f_int: &mut Vector,
        want_k: bool,
        trial_is_current: bool,
    ) -> Result<(), SolveError> {
        // the trial states move to the current u
        self.f_int_committed = None;
        let u_loc: Vec<f64> = self.local_u()?;
        let u0_loc: Vec<f64> = self
            .gather_committed
            .gather(&self.u_committed)?
            .read(|s| s.to_vec())?;
        let mut elements = ElementLoop {
            model_blocks: &mut self.blocks,
            scene: self.scene,
            disc: &self.disc,
            solid_geo: &self.solid_geo,
            iface_geo: &self.iface_geo,
            elem_block: &self.elem_block,
            active_block: &self.active_block,
            increment: (&u_loc, &u0_loc),
            trial_is_current,
        };
        let (slots, k) = (&self.slots, &mut self.k);
        let started = std::time::Instant::now();
        let (local, diagonals) = f_int.write(|f| {
            f.fill(0.0);
            match want_k {
                false => Ok(elements.run(f, None)),
                true => k.overwrite_values(|diag, off| {
                    diag.fill(0.0);
                    off.fill(0.0);
                    elements.run(f, Some((slots, diag, off)))
                }),
            }
        })??;
        self.element_seconds += started.elapsed().as_secs_f64();
        if want_k {
            // stiffness diagonals of the owned elements, for the Dirichlet scaling (an exact
            // sum: the same at any rank count)
            let n = sum_u64(self.comm, diagonals.len() as u64);
            let s = exact_sum(self.comm, diagonals.iter().copied());
            self.dirichlet_diag = if n > 0 && s > 0.0 { s / n as f64 } else { 1.0 };
        }
        local
    }
}

/// The owned entries of K the element loop adds to: where they are, and the values of the
/// diagonal and off-diagonal blocks.
type KSums<'k> = (&'k TangentSlots, &'k mut [f64], &'k mut [f64]);

/// The placed elements of this rank evaluated at the increment u − u_committed (the fields of
/// [`Model`] the element loop needs).
struct ElementLoop<'m> {
    model_blocks: &'m mut [BlockStates],
    scene: &'m crate::scene::Scene,
    disc: &'m super::discretization::Discretization,
    solid_geo: &'m [Option<Hex8Geometry>],
    iface_geo: &'m [Option<Interface8Geometry>],
    elem_block: &'m [(usize, usize)],
    active_block: &'m [bool],
    /// u and u_committed at the local DOFs.
    increment: (&'m [f64], &'m [f64]),
    trial_is_current: bool,
}

impl ElementLoop<'_> {
    /// Adds every placed element's owned rows to `f` (the owned entries of f_int) and, with
    /// `k`, to K; stops at the first material failure. Returns it and the absolute diagonals
    /// of the owned elements' K_e.
    fn run(&mut self, f: &mut [f64], mut k: Option<KSums>) -> (Result<(), SolveError>, Vec<f64>) {
        let mut diagonals = Vec::new();
        for i in 0..self.disc.elements.len() {
            if !self.active_block[self.elem_block[i].0] {
                continue;
            }
            let (fe, ke) = match self.element(i, k.is_some()) {
                Ok(r) => r,
                Err(e) => return (Err(e), diagonals),
            };
            let loc = &self.disc.element_local[i];
            for (r, &v) in fe.iter().enumerate() {
                let d = self.disc.local_dofs[3 * loc[r / 3] as usize + r % 3];
                if self.disc.owns_dof(d) {
                    f[d as usize - self.disc.dof_lo] += v;
                }
            }
            if let (Some((slots, diag, off)), Some(ke)) = (k.as_mut(), ke) {
                if self.disc.element_owned[i] {
                    diagonals.extend(ke.diagonal().iter().map(|v| v.abs()));
                }
                slots.add(i, &ke, diag, off);
            }
        }
        (Ok(()), diagonals)
    }

    /// f_e and (with `want_k`) K_e of the `i`-th element of this rank at the increment.
    fn element(&mut self, i: usize, want_k: bool) -> Result<(Vector24, Option<Box<Matrix24>>), SolveError> {
        let mesh = &self.scene.mesh;
        let (b, be) = self.elem_block[i];
        let loc = &self.disc.element_local[i];
        let (u, u0) = self.increment;
        let d_u = Vector24::from_fn(|r, _| {
            let l = 3 * loc[r / 3] as usize + r % 3;
            u[l] - u0[l]
        });
        let evaluated = match &mut self.model_blocks[b] {
            BlockStates::Solid(block) => {
                let geo = self.solid_geo[i]
                    .as_ref()
                    .expect("solid geometry built at set-up");
                if self.trial_is_current {
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
                if self.trial_is_current {
                    let r = block.evaluate_trial(be, geo);
                    Ok((r.f_int, r.k.filter(|_| want_k)))
                } else {
                    block.evaluate(be, geo, &d_u, want_k).map(|r| (r.f_int, r.k))
                }
            }
        };
        let e = self.disc.elements[i] as usize;
        evaluated.map_err(|m| SolveError::Material {
            element: mesh.elements[e].id,
            reason: format!("{}: {}", element_place(mesh, e), m.reason),
        })
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
