//! Parameters of the generated CFRD ([`CfrdSpec`], the scene's `mesh.cfrd`), their checks, and
//! the layout of layers, slab stages and panels derived from them ([`super::dam_generator`]).

use crate::mesh::error::MeshError;

/// The three fill zones of the generated dam, in x order.
pub(super) const ZONES: [&str; 3] = ["cushion", "transition", "rockfill"];

/// Most impoundment stages of a generated schedule (`mesh.cfrd.impoundment_stages`).
pub const MAX_IMPOUNDMENT_STAGES: usize = 10_000;

/// Parameters of [`cfrd_mesh`](super::dam_generator::cfrd_mesh) (the scene's `mesh.cfrd`); omitted keys take the seed dam's
/// values (`seed/summary.md` §2.1, `spec/seismic.md` §5).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct CfrdSpec {
    /// Maximum dam height H (m). Seed: 171.
    pub height: f64,
    /// Elevation of the base, i.e. of the valley bottom (m). Seed: 2681. The mesh's z is the
    /// absolute elevation; the crest is at `base_elevation + height`.
    pub base_elevation: f64,
    /// Crest length along the dam axis (m). Seed: 355.
    pub crest_length: f64,
    /// Crest width (m). Seed: not given; 10.
    pub crest_width: f64,
    /// Upstream slope m_u (horizontal per vertical). Seed: 1.4.
    pub upstream_slope: f64,
    /// Downstream slope m_d (horizontal per vertical). Seed: 1.4.
    pub downstream_slope: f64,
    /// Width of the valley bottom b (m), 0 < b < crest_length. Default 100 (abutment slopes
    /// tan θ = 2H/(355 − b) ≈ 53°).
    pub valley_bottom_width: f64,
    /// Share of the abutment run (crest_length − b) on the left bank (y < 0), in (0, 1);
    /// default 0.5 (symmetric valley).
    pub left_share: f64,
    /// Horizontal width of the cushion zone (m). Default 3.
    pub cushion_width: f64,
    /// Horizontal width of the transition zone (m). Default 4.
    pub transition_width: f64,
    /// Top elevations of the slab stages (m), increasing, the last one at the crest.
    /// Seed: [2737, 2805, 2852].
    pub slab_stage_tops: Vec<f64>,
    /// Fill elevation at which slab stage 1 is cast (m), between the top of stage 1 and the
    /// crest. Seed: 2780 (step 54 of 86). The other stages are cast after the fill.
    pub slab_cast_elevation: f64,
    /// Slab thickness at the crest (m). Seed: 0.30.
    pub slab_thickness_crest: f64,
    /// Increase of the slab thickness per metre below the crest (m/m). Seed: 0.0035.
    pub slab_thickness_gradient: f64,
    /// Nominal slab panel width along the axis (m), i.e. the spacing of the vertical joints.
    /// Default 15.
    pub panel_width: f64,
    /// Elements along the axis per slab panel (≥ 1).
    pub elements_per_panel: usize,
    /// Fill layers = construction steps = element layers over the height (≥ the number of
    /// elevation segments, 4 for the seed; at most 100 000). Seed: 86. The whole mesh may have at
    /// most [`super::generate::MAX_GENERATED_NODES`] nodes.
    pub fill_layers: usize,
    /// Elements across the main rockfill zone (≥ 1).
    pub rockfill_elements: usize,
    /// Final reservoir level (m, elevation), above the base and at most the crest. Seed: 2840.
    pub impoundment_level: f64,
    /// Number of impoundment stages, 1 to [`MAX_IMPOUNDMENT_STAGES`].
    pub impoundment_stages: usize,
    /// Load steps of each fill-layer stage (1 to `scene::ranges::MAX_LOAD_STEPS`); default: `solver.load_steps`, as for the other
    /// stages. The seed places its 86 layers (about 2 m each) in one step each. Fewer steps are
    /// not cheaper with the GP rockfill: on the fine seed mesh two steps per layer took about
    /// twice as long as eight (`scripts/make_seed_scenes.sh`), as a new layer starts unconfined.
    pub fill_load_steps: Option<u32>,
    /// Unit weight of water γ_w (N/m³) for the impoundment loads. Default 9810.
    pub water_unit_weight: f64,
}

impl Default for CfrdSpec {
    /// The seed dam at the paper's resolution (about 76 000 elements).
    fn default() -> Self {
        CfrdSpec {
            height: 171.0,
            base_elevation: 2681.0,
            crest_length: 355.0,
            crest_width: 10.0,
            upstream_slope: 1.4,
            downstream_slope: 1.4,
            valley_bottom_width: 100.0,
            left_share: 0.5,
            cushion_width: 3.0,
            transition_width: 4.0,
            slab_stage_tops: vec![2737.0, 2805.0, 2852.0],
            slab_cast_elevation: 2780.0,
            slab_thickness_crest: 0.30,
            slab_thickness_gradient: 0.0035,
            panel_width: 15.0,
            elements_per_panel: 2,
            fill_layers: 86,
            rockfill_elements: 14,
            impoundment_level: 2840.0,
            impoundment_stages: 6,
            fill_load_steps: None,
            water_unit_weight: 9810.0,
        }
    }
}

fn invalid(field: &str, reason: String) -> MeshError {
    MeshError::InvalidParameter {
        field: format!("mesh.cfrd.{field}"),
        reason,
    }
}

fn positive(field: &str, v: f64) -> Result<(), MeshError> {
    super::generate::positive(&format!("mesh.cfrd.{field}"), v)
}

fn non_negative(field: &str, v: f64) -> Result<(), MeshError> {
    super::generate::non_negative(&format!("mesh.cfrd.{field}"), v)
}

/// Geometry derived from a checked spec.
pub(super) struct Layout {
    /// Relative heights (above the base) of the layer boundaries.
    pub(super) h: Vec<f64>,
    /// Element rows [start, end) of each slab stage.
    pub(super) stage_rows: Vec<(usize, usize)>,
    /// Layer index after which slab stage 1 is cast (its top is the cast elevation).
    pub(super) cast_layer: usize,
    /// Abutment runs (horizontal per vertical) on the left and right.
    pub(super) run: [f64; 2],
    /// y of the edges of the central part.
    pub(super) central: [f64; 2],
    /// Panels in the left fan, the central part, the right fan.
    pub(super) panels: [usize; 3],
}

impl CfrdSpec {
    /// Crest elevation (m).
    pub fn crest_elevation(&self) -> f64 {
        self.base_elevation + self.height
    }

    /// Slab thickness (m) at elevation `z`: t = t_crest + g·(z_crest − z) (seed §2.1).
    pub fn slab_thickness(&self, z: f64) -> f64 {
        self.slab_thickness_crest + self.slab_thickness_gradient * (self.crest_elevation() - z)
    }

    /// About how many nodes the mesh has (an upper bound: the rockfill grid counted twice
    /// stands for the grid, the slab and the plinth), the number checked against
    /// [`super::generate::MAX_GENERATED_NODES`]; an invalid spec is an error as in
    /// [`cfrd_mesh`](super::dam_generator::cfrd_mesh). Cheap: nothing of the mesh is built.
    pub fn approximate_nodes(&self) -> Result<u128, MeshError> {
        Ok(self.nodes_of(self.layout()?.panels))
    }

    /// The estimate of [`CfrdSpec::approximate_nodes`] for the panels of the left fan, the
    /// central part and the right fan.
    fn nodes_of(&self, panels: [usize; 3]) -> u128 {
        let ny = panels.iter().map(|&p| p as u128).sum::<u128>() * self.elements_per_panel as u128;
        (self.rockfill_elements as u128 + 3) * (ny + 1) * (self.fill_layers as u128 + 1) * 2
    }

    /// Checks the values; errors name the YAML path `mesh.cfrd.<field>`.
    pub(super) fn layout(&self) -> Result<Layout, MeshError> {
        self.check_section()?;
        self.check_counts()?;
        let tol = 1e-9 * self.height;
        self.check_elevations(tol)?;
        let h = self.layer_heights(tol)?;
        let zb = self.base_elevation;
        let row_at = |z: f64| -> usize {
            let target = z - zb;
            h.iter()
                .enumerate()
                .min_by(|a, b| (a.1 - target).abs().total_cmp(&(b.1 - target).abs()))
                .map(|(k, _)| k)
                .unwrap_or(0)
        };
        let mut stage_rows = Vec::with_capacity(self.slab_stage_tops.len());
        let mut start = 0;
        for &z in &self.slab_stage_tops {
            let end = row_at(z);
            stage_rows.push((start, end));
            start = end;
        }
        let cast_layer = row_at(self.slab_cast_elevation);
        let (run, half, panels) = self.canyon_panels()?;
        Ok(Layout {
            h,
            stage_rows,
            cast_layer,
            run,
            central: [-half, half],
            panels,
        })
    }

    /// Checks the dimensions of the section and the canyon.
    fn check_section(&self) -> Result<(), MeshError> {
        positive("height", self.height)?;
        if !self.base_elevation.is_finite() {
            return Err(invalid("base_elevation", "must be finite".into()));
        }
        positive("crest_length", self.crest_length)?;
        positive("crest_width", self.crest_width)?;
        non_negative("upstream_slope", self.upstream_slope)?;
        non_negative("downstream_slope", self.downstream_slope)?;
        positive("valley_bottom_width", self.valley_bottom_width)?;
        if self.valley_bottom_width >= self.crest_length {
            return Err(invalid(
                "valley_bottom_width",
                format!(
                    "{} m must be smaller than crest_length ({} m)",
                    self.valley_bottom_width, self.crest_length
                ),
            ));
        }
        if !(self.left_share > 0.0 && self.left_share < 1.0) {
            return Err(invalid(
                "left_share",
                format!("must lie in (0, 1), got {}", self.left_share),
            ));
        }
        positive("cushion_width", self.cushion_width)?;
        positive("transition_width", self.transition_width)?;
        if self.cushion_width + self.transition_width >= self.crest_width {
            return Err(invalid(
                "transition_width",
                format!(
                    "cushion_width + transition_width = {} m leaves no main rockfill under the {} m crest",
                    self.cushion_width + self.transition_width,
                    self.crest_width
                ),
            ));
        }
        positive("slab_thickness_crest", self.slab_thickness_crest)?;
        non_negative("slab_thickness_gradient", self.slab_thickness_gradient)?;
        positive("panel_width", self.panel_width)
    }

    /// Checks the element and stage counts and the unit weight of water.
    fn check_counts(&self) -> Result<(), MeshError> {
        if self.elements_per_panel == 0 {
            return Err(invalid("elements_per_panel", "must be at least 1".into()));
        }
        if self.rockfill_elements == 0 {
            return Err(invalid("rockfill_elements", "must be at least 1".into()));
        }
        if !(1..=MAX_IMPOUNDMENT_STAGES).contains(&self.impoundment_stages) {
            return Err(invalid(
                "impoundment_stages",
                format!(
                    "{} must lie in [1, {MAX_IMPOUNDMENT_STAGES}]",
                    self.impoundment_stages
                ),
            ));
        }
        let max_steps = crate::scene::ranges::MAX_LOAD_STEPS;
        if let Some(n) = self.fill_load_steps.filter(|n| !(1..=max_steps).contains(n)) {
            return Err(invalid(
                "fill_load_steps",
                format!("{n} must lie in [1, {max_steps}]"),
            ));
        }
        if !(self.water_unit_weight.is_finite()
            && self.water_unit_weight > 100.0
            && self.water_unit_weight < 1e5)
        {
            return Err(invalid(
                "water_unit_weight",
                format!("{} N/m³ is not plausible (SI: 9810)", self.water_unit_weight),
            ));
        }
        Ok(())
    }

    /// Checks the slab stage tops, the cast elevation and the reservoir level against the base
    /// and the crest, `tol` the tolerance of elevations.
    fn check_elevations(&self, tol: f64) -> Result<(), MeshError> {
        let (zb, zc) = (self.base_elevation, self.crest_elevation());
        let tops = &self.slab_stage_tops;
        if tops.is_empty() {
            return Err(invalid("slab_stage_tops", "lists no stage".into()));
        }
        for (s, &z) in tops.iter().enumerate() {
            let below = if s == 0 { zb } else { tops[s - 1] };
            if !(z.is_finite() && z > below + tol) {
                return Err(invalid(
                    &format!("slab_stage_tops[{s}]"),
                    format!("{z} m must lie above {below} m (the base or the previous stage top)"),
                ));
            }
        }
        if (tops[tops.len() - 1] - zc).abs() > tol {
            return Err(invalid(
                &format!("slab_stage_tops[{}]", tops.len() - 1),
                format!(
                    "the last stage must end at the crest, {zc} m, got {} m",
                    tops[tops.len() - 1]
                ),
            ));
        }
        let cast = self.slab_cast_elevation;
        if !(cast.is_finite() && cast >= tops[0] - tol && cast <= zc + tol) {
            return Err(invalid(
                "slab_cast_elevation",
                format!(
                    "{cast} m must lie between the top of slab stage 1 ({} m) and the crest ({zc} m)",
                    tops[0]
                ),
            ));
        }
        let level = self.impoundment_level;
        if !(level.is_finite() && level > zb && level <= zc + tol) {
            return Err(invalid(
                "impoundment_level",
                format!("{level} m must lie above the base ({zb} m) and at most at the crest ({zc} m)"),
            ));
        }
        Ok(())
    }

    /// Relative heights of the layer boundaries: the breakpoints (base, slab stage tops, cast
    /// elevation) split the height into segments, which share the layers by largest remainder.
    fn layer_heights(&self, tol: f64) -> Result<Vec<f64>, MeshError> {
        let zb = self.base_elevation;
        let cast = self.slab_cast_elevation;
        let mut breaks: Vec<f64> = vec![0.0];
        for z in self.slab_stage_tops.iter().chain(std::iter::once(&cast)) {
            let h = (z - zb).clamp(0.0, self.height);
            if breaks.iter().all(|b| (b - h).abs() > tol) {
                breaks.push(h);
            }
        }
        breaks.sort_by(f64::total_cmp);
        let segments = breaks.len() - 1;
        let nz = self.fill_layers;
        if nz < segments {
            return Err(invalid(
                "fill_layers",
                format!("{nz} is fewer than the {segments} elevation segments between the base, the slab stage tops and the cast elevation"),
            ));
        }
        if nz > 100_000 {
            return Err(invalid(
                "fill_layers",
                format!("{nz} is too many (at most 100000)"),
            ));
        }
        let lens: Vec<f64> = breaks.windows(2).map(|w| w[1] - w[0]).collect();
        let count = self.layers_per_segment(segments, &lens);
        let mut h = vec![0.0];
        for (s, &c) in count.iter().enumerate() {
            for q in 1..=c {
                h.push(breaks[s] + lens[s] * q as f64 / c as f64);
            }
        }
        Ok(h)
    }

    /// Layers of each of the `segments` elevation segments of lengths `lens`: one each, the
    /// others by largest remainder of their share of the height.
    fn layers_per_segment(&self, segments: usize, lens: &[f64]) -> Vec<usize> {
        let nz = self.fill_layers;
        let mut count = vec![1usize; segments];
        let spare = (nz - segments) as f64;
        let exact: Vec<f64> = lens.iter().map(|l| spare * l / self.height).collect();
        for (c, e) in count.iter_mut().zip(&exact) {
            *c += e.floor() as usize;
        }
        let mut order: Vec<usize> = (0..segments).collect();
        order.sort_by(|&a, &b| {
            (exact[b] - exact[b].floor())
                .total_cmp(&(exact[a] - exact[a].floor()))
                .then(a.cmp(&b))
        });
        let mut left = nz - count.iter().sum::<usize>();
        for &s in order.iter().cycle() {
            if left == 0 {
                break;
            }
            count[s] += 1;
            left -= 1;
        }
        count
    }

    /// The abutment runs, the half width of the central part and the panels of the left fan,
    /// the central part and the right fan; an error if the mesh would have too many nodes.
    fn canyon_panels(&self) -> Result<([f64; 2], f64, [usize; 3]), MeshError> {
        let runs = (self.crest_length - self.valley_bottom_width) / self.height;
        let run = [self.left_share * runs, (1.0 - self.left_share) * runs];
        let w = self.panel_width;
        let n_central = ((self.valley_bottom_width / w + 1e-9).floor() as usize).saturating_sub(2);
        let half = 0.5 * n_central as f64 * w;
        let half_bottom = 0.5 * self.valley_bottom_width;
        let fan_left = half_bottom + run[0] * self.height - half;
        let fan_right = half_bottom + run[1] * self.height - half;
        let panels = [
            ((fan_left / w).round() as usize).max(1),
            n_central,
            ((fan_right / w).round() as usize).max(1),
        ];
        let nodes = self.nodes_of(panels);
        let most = super::generate::MAX_GENERATED_NODES;
        if nodes > most as u128 {
            return Err(invalid(
                "fill_layers",
                format!(
                    "with rockfill_elements {}, elements_per_panel {} and panel_width {} m the mesh \
                     would have about {nodes} nodes, more than the limit of {most}",
                    self.rockfill_elements, self.elements_per_panel, self.panel_width
                ),
            ));
        }
        Ok((run, half, panels))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::dam_generator::cfrd_mesh;

    #[test]
    fn bad_spec_values_name_their_yaml_path() {
        let seed = CfrdSpec {
            fill_layers: 8,
            rockfill_elements: 2,
            ..CfrdSpec::default()
        };
        let cases: Vec<(CfrdSpec, &str)> = vec![
            (
                CfrdSpec {
                    height: -1.0,
                    ..seed.clone()
                },
                "mesh.cfrd.height",
            ),
            (
                CfrdSpec {
                    valley_bottom_width: 400.0,
                    ..seed.clone()
                },
                "mesh.cfrd.valley_bottom_width",
            ),
            (
                CfrdSpec {
                    left_share: 1.0,
                    ..seed.clone()
                },
                "mesh.cfrd.left_share",
            ),
            (
                CfrdSpec {
                    transition_width: 8.0,
                    ..seed.clone()
                },
                "mesh.cfrd.transition_width",
            ),
            (
                CfrdSpec {
                    slab_stage_tops: vec![2737.0, 2700.0, 2852.0],
                    ..seed.clone()
                },
                "mesh.cfrd.slab_stage_tops[1]",
            ),
            (
                CfrdSpec {
                    slab_stage_tops: vec![2737.0, 2850.0],
                    ..seed.clone()
                },
                "mesh.cfrd.slab_stage_tops[1]",
            ),
            (
                CfrdSpec {
                    slab_cast_elevation: 2700.0,
                    ..seed.clone()
                },
                "mesh.cfrd.slab_cast_elevation",
            ),
            (
                CfrdSpec {
                    fill_layers: 3,
                    ..seed.clone()
                },
                "mesh.cfrd.fill_layers",
            ),
            (
                CfrdSpec {
                    elements_per_panel: 0,
                    ..seed.clone()
                },
                "mesh.cfrd.elements_per_panel",
            ),
            (
                CfrdSpec {
                    impoundment_level: 2900.0,
                    ..seed.clone()
                },
                "mesh.cfrd.impoundment_level",
            ),
            (
                CfrdSpec {
                    panel_width: 0.0,
                    ..seed.clone()
                },
                "mesh.cfrd.panel_width",
            ),
        ];
        for (spec, path) in cases {
            let err = cfrd_mesh(&spec).expect_err(path).to_string();
            assert!(err.contains(&format!("{path}:")), "{path}: {err}");
        }
    }
}
