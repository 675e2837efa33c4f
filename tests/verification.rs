//! Verification of the static solver in one process (an MPI singleton with PETSc):
//!
//! * issue 2, acceptance 1 — patch test: a distorted hexahedral patch reproduces a linear
//!   displacement field exactly (1e-10) and a uniform stress;
//! * issue 2, acceptance 2 — a laterally confined column under self-weight matches the closed
//!   form, and the errors fall at the expected rates under refinement (L2 displacement O(h²),
//!   L2 stress O(h));
//! * issue 4, acceptance 1 — the hydrostatic resultant on the inclined upstream face of a dam
//!   section equals ρ_w·g·h²/2 (horizontal) and ρ_w·g·h²·m/2 (vertical, the water wedge on a
//!   1:m slope) per unit width, read from the reactions.
//!
//! MPI may be initialized once per process, so this file holds a single test that runs every
//! check in turn.

use cfrd::element::quadrature::HEX_GAUSS_2X2X2;
use cfrd::element::shape::hex8_shape;
use cfrd::linalg::petsc::Petsc;
use cfrd::scene::Scene;
use cfrd::solver::discretization::Discretization;
use cfrd::solver::{mesh_cells, LocalResults, Problem, SolveReport};
use partition::Partition;
use std::path::Path;

fn solve(petsc: &Petsc, scene: &Scene) -> LocalResults {
    let cells = mesh_cells(&scene.mesh);
    let n = scene.mesh.num_nodes();
    let part = Partition::new(&cells, n, 1, vec![0; cells.len()]);
    let disc = Discretization::new(&cells, n, part, 0);
    let world = mpi::topology::SimpleCommunicator::world();
    let mut problem = Problem::new(petsc, &world, scene, cells, disc).expect("setup");
    let mut report = SolveReport::default();
    problem.begin_stage(0).expect("stage");
    problem.solve_step(0.0, 1.0, &mut report).expect("solve");
    problem.results().expect("results")
}

const ELASTIC: &str = "
materials:
  soil: { model: elastic, young: 5.0e7, poisson: 0.3, density: 2000.0 }
";

fn patch_test(petsc: &Petsc) {
    let text = format!(
        "name: patch\nunits: SI\nmesh:\n  box: {{ size: [1.0, 2.0, 1.5], divisions: [3, 3, 3], jitter: 0.2, seed: 7 }}\n{ELASTIC}\
         blocks: {{ layer_1: {{ material: soil }} }}\n\
         boundary: [{{ set: zmin, fix: [x, y, z] }}]\n\
         solver: {{ petsc_options: '-ksp_type preonly -pc_type lu' }}\n"
    );
    // the scene is held by its base (a body free to move is refused); the test then fixes
    // every boundary node to the exact displacement
    let mut scene = Scene::from_str(&text, "patch", Path::new(".")).expect("scene");
    let a = [1e-3, -2e-3, 5e-4];
    let g = [[1e-3, 2e-4, -3e-4], [5e-4, -8e-4, 1e-4], [-2e-4, 3e-4, 6e-4]];
    let exact = |x: &[f64; 3]| -> [f64; 3] {
        std::array::from_fn(|i| a[i] + (0..3).map(|j| g[i][j] * x[j]).sum::<f64>())
    };
    let mut boundary: Vec<u32> = Vec::new();
    for s in ["xmin", "xmax", "ymin", "ymax", "zmin", "zmax"] {
        boundary.extend(&scene.mesh.node_sets[s]);
    }
    boundary.sort_unstable();
    boundary.dedup();
    scene.fixed = boundary
        .iter()
        .flat_map(|&n| {
            let u = exact(&scene.mesh.coords[n as usize]);
            (0..3).map(move |c| (n, c as u8, u[c]))
        })
        .collect();
    let res = solve(petsc, &scene);
    let interior = scene.mesh.num_nodes() - boundary.len();
    assert!(interior >= 8, "the patch must have free interior nodes");
    let mut worst = 0.0f64;
    for (i, &n) in res.nodes.iter().enumerate() {
        let u = exact(&scene.mesh.coords[n as usize]);
        for c in 0..3 {
            worst = worst.max((res.displacement[i][c] - u[c]).abs());
        }
    }
    let scale = 3e-3;
    println!(
        "patch test: max |u - u_exact| / |u| = {:.2e} over {} interior nodes",
        worst / scale,
        interior
    );
    assert!(
        worst / scale < 1e-10,
        "patch test displacement error {:.3e}",
        worst / scale
    );
    // uniform stress σ = D ε with ε the symmetric part of G (engineering shear)
    let eps = [
        g[0][0],
        g[1][1],
        g[2][2],
        g[0][1] + g[1][0],
        g[1][2] + g[2][1],
        g[0][2] + g[2][0],
    ];
    let d = cfrd::material::elastic::isotropic_stiffness(5.0e7, 0.3);
    let sig = d * nalgebra::SVector::<f64, 6>::from(eps);
    for s in &res.stress {
        let err = (s.0 - sig).norm() / sig.norm();
        assert!(err < 1e-9, "patch test stress error {err:.3e}");
    }
}

/// Errors of the confined column with `nz` elements over the height: (h, L2 error of u_z
/// relative to the L2 norm of u_z, L2 error of σ_zz relative to its L2 norm).
fn column(petsc: &Petsc, nz: usize) -> (f64, f64, f64) {
    let h_col = 10.0;
    let text = format!(
        "name: column\nunits: SI\nmesh:\n  box: {{ size: [1.0, 1.0, {h_col}], divisions: [1, 1, {nz}] }}\n{ELASTIC}\
         blocks: {{ layer_1: {{ material: soil }} }}\n\
         boundary: [{{ set: zmin, fix: [x, y, z] }}, {{ set: xmin, fix: [x] }}, {{ set: xmax, fix: [x] }},\
         {{ set: ymin, fix: [y] }}, {{ set: ymax, fix: [y] }}]\n\
         loads: {{ gravity: {{ g: [0.0, 0.0, -9.81] }} }}\n\
         solver: {{ rtol: 1.0e-13 }}\n"
    );
    let scene = Scene::from_str(&text, "column", Path::new(".")).expect("scene");
    let res = solve(petsc, &scene);
    let (e, nu, rho, g) = (5.0e7, 0.3, 2000.0, 9.81);
    let m = e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let u_exact = |z: f64| -rho * g / m * (h_col * z - 0.5 * z * z);
    let s_exact = |z: f64| -rho * g * (h_col - z);
    let mut uz = vec![0.0; scene.mesh.num_nodes()];
    for (i, &n) in res.nodes.iter().enumerate() {
        uz[n as usize] = res.displacement[i][2];
    }
    // top settlement against ρgH²/(2M)
    let top = scene.mesh.node_sets["zmax"][0] as usize;
    let settle = -rho * g * h_col * h_col / (2.0 * m);
    assert!(
        (uz[top] - settle).abs() / settle.abs() < 1e-8,
        "top settlement {} vs {settle}",
        uz[top]
    );
    let (mut eu, mut nu2, mut es, mut ns) = (0.0, 0.0, 0.0, 0.0);
    for (k, el) in scene.mesh.elements.iter().enumerate() {
        let x = scene.mesh.element_coords(k);
        let geo = cfrd::element::hex8::Hex8Geometry::new(&x).expect("valid");
        let ue = nalgebra::SVector::<f64, 24>::from_fn(|r, _| {
            if r % 3 == 2 {
                uz[el.nodes[r / 3] as usize]
            } else {
                0.0
            }
        });
        let eps = geo.strain_increments(&ue);
        for (q, qp) in HEX_GAUSS_2X2X2.iter().enumerate() {
            let nq = hex8_shape(&qp.xi);
            let z: f64 = (0..8).map(|a| nq[a] * x[a][2]).sum();
            let uh: f64 = (0..8).map(|a| nq[a] * uz[el.nodes[a] as usize]).sum();
            let sh = m * eps[q].0[2];
            let w = geo.det_j_w[q];
            eu += w * (uh - u_exact(z)).powi(2);
            nu2 += w * u_exact(z).powi(2);
            es += w * (sh - s_exact(z)).powi(2);
            ns += w * s_exact(z).powi(2);
        }
    }
    (h_col / nz as f64, (eu / nu2).sqrt(), (es / ns).sqrt())
}

/// Hydrostatic load alone (no gravity) on a 1:1.4 dam section, reservoir level at an element
/// boundary so the 2×2 face quadrature integrates the linear pressure exactly: the reactions
/// balance the water load, ΣR = −(ρ_w g h²/2, 0, −ρ_w g h² m/2)·L up to the sign of the face.
fn hydrostatic_resultant(petsc: &Petsc) {
    let (height, slope, length, nz) = (80.0, 1.4, 30.0, 8);
    let level = height * 6.0 / nz as f64;
    let text = format!(
        "name: hydrostatic\nunits: SI\nmesh:\n  dam: {{ height: {height}, crest_width: 8.0, upstream_slope: {slope}, \
         downstream_slope: 1.6, length: {length}, divisions: [10, 3, {nz}] }}\n\
         materials:\n  fill: {{ model: elastic, young: 1.0e9, poisson: 0.25, density: 2000.0 }}\n\
         blocks:\n  layer_1: {{ material: fill }}\n\
         boundary:\n  - {{ set: base, fix: [x, y, z] }}\n  - {{ set: ymin, fix: [y] }}\n  - {{ set: ymax, fix: [y] }}\n\
         loads:\n  hydrostatic:\n    - {{ faces: upstream, level: {level} }}\n"
    );
    let scene = Scene::from_str(&text, "hydrostatic", Path::new(".")).expect("scene");
    let res = solve(petsc, &scene);
    let sum = res
        .reaction
        .iter()
        .fold([0.0; 3], |a, r| [a[0] + r[0], a[1] + r[1], a[2] + r[2]]);
    let (rho_w_g, h) = (9810.0, level);
    let fx = rho_w_g * h * h / 2.0 * length;
    let fz = rho_w_g * h * h * slope / 2.0 * length;
    let (ex, ez) = ((sum[0].abs() - fx).abs() / fx, (sum[2].abs() - fz).abs() / fz);
    println!(
        "hydrostatic resultant, h = {h} m, 1:{slope} face, L = {length} m: ΣR = ({:.6e}, {:.3e}, {:.6e}) N; \
         ρw g h²/2·L = {fx:.6e}, ρw g h² m/2·L = {fz:.6e}; relative errors {ex:.1e}, {ez:.1e}",
        sum[0], sum[1], sum[2]
    );
    assert!(ex < 1e-9 && ez < 1e-9, "resultant errors {ex:.2e} {ez:.2e}");
    assert!(sum[1].abs() < 1e-9 * fx, "no force along the axis");
}

#[test]
fn static_solver_verification() {
    let universe = mpi::initialize().expect("MPI");
    let world = universe.world();
    let petsc = Petsc::initialize(&world).expect("PETSc");

    patch_test(&petsc);
    hydrostatic_resultant(&petsc);

    let runs: Vec<(f64, f64, f64)> = [2, 4, 8, 16].iter().map(|&nz| column(&petsc, nz)).collect();
    println!("confined column under self-weight (E = 50 MPa, ν = 0.3, H = 10 m):");
    println!("  h (m)   L2 error u_z   rate   L2 error σ_zz   rate");
    for (i, r) in runs.iter().enumerate() {
        let rates = if i == 0 {
            ("   - ".to_string(), "   - ".to_string())
        } else {
            let p = &runs[i - 1];
            let ratio = (p.0 / r.0).ln();
            (
                format!("{:5.2}", (p.1 / r.1).ln() / ratio),
                format!("{:5.2}", (p.2 / r.2).ln() / ratio),
            )
        };
        println!(
            "  {:5.3}   {:.4e}    {}   {:.4e}     {}",
            r.0, r.1, rates.0, r.2, rates.1
        );
    }
    for w in runs.windows(2) {
        let ratio = (w[0].0 / w[1].0).ln();
        let rate_u = (w[0].1 / w[1].1).ln() / ratio;
        let rate_s = (w[0].2 / w[1].2).ln() / ratio;
        assert!(
            (rate_u - 2.0).abs() < 0.15,
            "displacement L2 rate {rate_u:.3}, expected 2"
        );
        assert!(
            (rate_s - 1.0).abs() < 0.15,
            "stress L2 rate {rate_s:.3}, expected 1"
        );
    }
    drop(petsc);
}
