//! The rank-local results of the committed state: displacements from each node's placement,
//! reactions, mean element stresses and strains, interface tractions and jumps.

use super::error::SolveError;
use super::model::BlockStates;
use super::problem::Problem;
use super::report::{LocalResults, NodeMotion, ELEMENT_STATE};
use super::solid::Vector24;
use crate::tensor::{Strain6, Stress6};

impl Problem<'_> {
    /// Collects the rank-local results (owned nodes and elements) at the committed state.
    /// Collective.
    pub fn results(&mut self) -> Result<LocalResults, SolveError> {
        let mut out = self.node_results()?;
        out.motion = self.integrator.rates()?.map(|r| NodeMotion {
            velocity: r.velocity.chunks(3).map(|c| [c[0], c[1], c[2]]).collect(),
            acceleration: r
                .acceleration
                .chunks(3)
                .map(|c| std::array::from_fn(|k| c[k] + r.ground[k]))
                .collect(),
        });
        let u_loc = self.model.local_u()?;
        let model = &self.model;
        out.elements = model.disc.owned_elements.clone();
        for i in 0..model.disc.elements.len() {
            if !model.disc.element_owned[i] {
                continue;
            }
            let loc = &model.disc.element_local[i];
            let ue = Vector24::from_fn(|k, _| u_loc[3 * loc[k / 3] as usize + k % 3]) - model.elem_ref[i];
            self.element_result(i, &ue, &mut out);
        }
        Ok(out)
    }

    /// The committed state of the elements `elements` (mesh indices), [`ELEMENT_STATE`] values
    /// each: mean stress (6, Voigt, Pa), interface mean traction (τ_s, τ_a, t_n; Pa), mean jump
    /// since placement (δ_s, δ_a, δ_n; m) and mean opening (m), zeros where they do not apply
    /// (the fields of [`Problem::results`] for a few elements, e.g. the probes of seed
    /// Figs. 14, 18–20 at every time step). The same on every rank and rank count. Collective.
    pub fn element_states(&mut self, elements: &[usize]) -> Result<Vec<f64>, SolveError> {
        let u_loc = self.model.local_u()?;
        let model = &self.model;
        let mut local = Vec::with_capacity(ELEMENT_STATE * elements.len());
        for &e in elements {
            let owned = (0..model.disc.elements.len())
                .find(|&i| model.disc.element_owned[i] && model.disc.elements[i] as usize == e);
            let mut out = LocalResults::default();
            if let Some(i) = owned {
                let loc = &model.disc.element_local[i];
                let ue = Vector24::from_fn(|k, _| u_loc[3 * loc[k / 3] as usize + k % 3]) - model.elem_ref[i];
                self.element_result(i, &ue, &mut out);
            }
            let stress = out.stress.first().map_or([0.0; 6], |s| s.0.into());
            let iface = out.interface.first().copied().unwrap_or_default();
            let jump = out.jump.first().copied().unwrap_or_default();
            local.extend(stress);
            local.extend(iface.traction);
            local.extend(jump);
            local.push(iface.opening);
        }
        // one rank holds each element: the sum adds zeros to its values, exactly (+ 0.0 turns
        // a −0 into 0 first, which a sum on two ranks would)
        local.iter_mut().for_each(|v| *v += 0.0);
        Ok(crate::parallel::sum_f64_slice(self.comm, &local))
    }

    /// Displacements (from each node's placement) and reactions of the owned nodes.
    fn node_results(&mut self) -> Result<LocalResults, SolveError> {
        let mut f_int = self.model.u.duplicate()?;
        if !self.model.kept_forces_at(&self.model.u, &mut f_int)? {
            self.model.assemble(&mut f_int, false, false)?;
        }
        let f_ext = self.external_force(1.0)?;
        let mut reac = f_int;
        reac.axpy(-1.0, &f_ext)?;
        let reac_all: Vec<f64> = reac.read(|s| s.to_vec())?;
        let u_own: Vec<f64> = self.model.u.read(|s| s.to_vec())?;
        let is_fixed = self.constraints.mask(&self.model.disc);
        let mut out = LocalResults {
            nodes: self.model.disc.owned_nodes.clone(),
            ..Default::default()
        };
        for i in 0..self.model.disc.owned_nodes.len() {
            let o = self.node_offset[i];
            out.displacement.push([
                u_own[3 * i] - o[0],
                u_own[3 * i + 1] - o[1],
                u_own[3 * i + 2] - o[2],
            ]);
            out.reaction.push(std::array::from_fn(|c| {
                if is_fixed[3 * i + c] {
                    reac_all[3 * i + c]
                } else {
                    0.0
                }
            }));
        }
        Ok(out)
    }

    /// Appends the mean strain and stress (solids) or the interface output and mean jump
    /// (interfaces) of the `i`-th evaluated element (displacement `ue` since its placement) to
    /// `out`; zeros for an element not yet placed.
    fn element_result(&self, i: usize, ue: &Vector24, out: &mut LocalResults) {
        let model = &self.model;
        let (b, be) = model.elem_block[i];
        let (mut strain, mut stress) = (Strain6::default(), Stress6::default());
        let mut iface = Default::default();
        let mut jump = [0.0; 3];
        match &model.blocks[b] {
            _ if !model.active_block[b] => {}
            BlockStates::Solid(block) => {
                let geo = model.solid_geo[i]
                    .as_ref()
                    .expect("solid geometry built at set-up");
                strain = block.mean_strain(be, geo, ue);
                stress = block.mean_stress(be);
            }
            BlockStates::Interface(block) => {
                let geo = model.iface_geo[i]
                    .as_ref()
                    .expect("interface geometry built at set-up");
                let w = 1.0 / geo.area_w.len() as f64;
                for j in geo.jumps(ue) {
                    for c in 0..3 {
                        jump[c] += w * j[c];
                    }
                }
                iface = block.output(be);
            }
        }
        out.strain.push(strain);
        out.stress.push(stress);
        out.interface.push(iface);
        out.jump.push(jump);
    }
}
