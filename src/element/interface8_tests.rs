//! Tests of the 8-node interface element (spec §9.5: EL-1, EL-2, EL-3, JT-1, JT-2) and of its
//! tangent against central differences of its residual for every interface law.

use super::*;
use crate::element::hex8::{face_pressure_load, Hex8Geometry};
use crate::element::quadrature::HEX_GAUSS_3X3X3;
use crate::material::interface_gp::{GpInterface, GpInterfaceParams, StiffnessBasis, TangentChoice};
use crate::material::interface_hyperbolic::{HyperbolicInterface, HyperbolicParams};
use crate::material::interface_mc::{MohrCoulombInterface, MohrCoulombParams};
use crate::material::joint::{JointLaw, JointParams};
use crate::material::InterfaceModel;
use crate::tensor::Tangent6;
use nalgebra::{DMatrix, DVector, Matrix3};
use std::convert::Infallible;

const RULES: [InterfaceRule; 2] = [InterfaceRule::NewtonCotes, InterfaceRule::Gauss2x2];

/// Unit up-slope vector of the 1:1.4 upstream face in the project axes (x stream, y axis, z up).
fn slope_dir() -> Vector3<f64> {
    Vector3::new(1.4, 0.0, 1.0) / 2.96f64.sqrt()
}

/// Unit normal of the 1:1.4 upstream face pointing into the dam (downstream and down).
fn into_dam() -> Vector3<f64> {
    Vector3::new(1.0, 0.0, -1.4) / 2.96f64.sqrt()
}

/// Zero-thickness element from the 4 face nodes (face A = copy of face B).
fn zero_thickness(face: [Vector3<f64>; 4]) -> Coords8 {
    std::array::from_fn(|a| face[a % 4].into())
}

/// Rectangle on the 1:1.4 face: `ls` m up the slope, `la` m along the dam axis.
fn slope_rectangle(ls: f64, la: f64) -> Coords8 {
    let o = Vector3::new(3.0, 2.0, 1.0);
    let (s, y) = (slope_dir() * ls, Vector3::y() * la);
    zero_thickness([o, o + s, o + s + y, o + y])
}

/// A warped (non-planar), arbitrarily oriented element.
fn warped() -> Coords8 {
    let rot = nalgebra::Rotation3::from_euler_angles(0.4, -0.7, 1.1);
    let face = [
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(2.2, 0.1, 0.15),
        Vector3::new(2.5, 1.7, -0.1),
        Vector3::new(-0.3, 1.5, 0.05),
    ]
    .map(|p| rot * p + Vector3::new(1.0, -2.0, 0.5));
    zero_thickness(face)
}

/// A non-symmetric constant tangent (Pa/m).
fn nonsym_d() -> Tangent3 {
    Matrix3::new(3e7, 0.4e7, 2.0e8, -0.2e7, 2e7, -1.0e8, 0.5e7, 0.3e7, 1e10)
}

/// A nonlinear law with an exact tangent: T = D δ + β‖δ‖² δ, dT/dδ = D + β(2δδᵀ + ‖δ‖² I).
fn cubic_law(q: usize, d: &Local3, _f: &LocalFrame) -> Result<(Local3, Tangent3), Infallible> {
    let beta = 1e13 * (1.0 + 0.1 * q as f64);
    let dd = nonsym_d();
    let t = dd * d + d * (beta * d.norm_squared());
    let k = dd + (d * d.transpose() * 2.0 + Matrix3::identity() * d.norm_squared()) * beta;
    Ok((t, k))
}

/// Nodal values of a rigid motion u = t + ω × x.
fn rigid(x: &Coords8, t: Vector3<f64>, w: Vector3<f64>) -> Vector24 {
    let mut u = Vector24::zeros();
    for a in 0..8 {
        let v = t + w.cross(&Vector3::from(x[a]));
        u.fixed_rows_mut::<3>(3 * a).copy_from(&v);
    }
    u
}

/// u with face B at `ub` and face A at `ub + du` (uniform).
fn uniform_jump(ub: Vector3<f64>, du: Vector3<f64>) -> Vector24 {
    let mut u = Vector24::zeros();
    for a in 0..4 {
        u.fixed_rows_mut::<3>(3 * a).copy_from(&ub);
        u.fixed_rows_mut::<3>(3 * (a + 4)).copy_from(&(ub + du));
    }
    u
}

/// Central finite-difference Jacobian of the element residual `r(u)`.
fn fd_jacobian(u: &Vector24, h: f64, mut r: impl FnMut(&Vector24) -> Vector24) -> Matrix24 {
    let mut k = Matrix24::zeros();
    for j in 0..24 {
        let (mut up, mut um) = (*u, *u);
        up[j] += h;
        um[j] -= h;
        k.set_column(j, &((r(&up) - r(&um)) / (2.0 * h)));
    }
    k
}

/// Block-diagonal rotation Q = diag(R, …, R) of the 8 nodes to the local frame `f`.
fn local_rotation(f: &LocalFrame) -> Matrix24 {
    let mut q = Matrix24::zeros();
    for a in 0..8 {
        q.fixed_view_mut::<3, 3>(3 * a, 3 * a).copy_from(&f.rotation());
    }
    q
}

/// Central finite-difference Jacobian of `r(u)` in the local components of a planar element
/// (all points share `f`): column `3a + c` perturbs node `a` along local axis `c` by `h[c]`, so
/// a shear column never perturbs the stiff normal spring. Returns Q (∂r/∂u) Qᵀ.
fn fd_jacobian_local(
    u: &Vector24,
    f: &LocalFrame,
    h: [f64; 3],
    mut r: impl FnMut(&Vector24) -> Vector24,
) -> Matrix24 {
    let q = local_rotation(f);
    let mut k = Matrix24::zeros();
    for j in 0..24 {
        let (a, c) = (j / 3, j % 3);
        let mut e = Local3::zeros();
        e[c] = h[c];
        let v = f.to_global(&e);
        let (mut up, mut um) = (*u, *u);
        for i in 0..3 {
            up[3 * a + i] += v[i];
            um[3 * a + i] -= v[i];
        }
        k.set_column(j, &(q * (r(&up) - r(&um)) / (2.0 * h[c])));
    }
    k
}

/// Errors of K (global) against the local FD Jacobian `kfl`, per block of local components:
/// `[ss, sn, ns, nn]` (rows shear/normal × columns shear/normal), each relative to the largest
/// |K_fd| entry of its block; the coupling blocks sn and ns (zero for some laws) are measured
/// against at least the largest shear–shear entry.
fn local_errors(k: &Matrix24, kfl: &Matrix24, f: &LocalFrame) -> [f64; 4] {
    let q = local_rotation(f);
    let kl = q * k * q.transpose();
    let block = |row_n: bool, col_n: bool| {
        let (mut num, mut den) = (0.0f64, 0.0f64);
        for i in (0..24).filter(|i| (i % 3 == 2) == row_n) {
            for j in (0..24).filter(|j| (j % 3 == 2) == col_n) {
                num = num.max((kl[(i, j)] - kfl[(i, j)]).abs());
                den = den.max(kfl[(i, j)].abs());
            }
        }
        (num, den)
    };
    let (ss, ss_scale) = block(false, false);
    let (sn, sn_scale) = block(false, true);
    let (ns, ns_scale) = block(true, false);
    let (nn, nn_scale) = block(true, true);
    [
        ss / ss_scale,
        sn / sn_scale.max(ss_scale),
        ns / ns_scale.max(ss_scale),
        nn / nn_scale,
    ]
}

#[test]
fn rule_names_and_default() {
    assert_eq!(InterfaceRule::default(), InterfaceRule::NewtonCotes);
    assert_eq!(
        serde_yaml::to_string(&InterfaceRule::NewtonCotes).unwrap().trim(),
        "newton_cotes"
    );
    assert_eq!(
        serde_yaml::to_string(&InterfaceRule::Gauss2x2).unwrap().trim(),
        "gauss2x2"
    );
    let r: InterfaceRule = serde_yaml::from_str("gauss2x2").unwrap();
    assert_eq!(r, InterfaceRule::Gauss2x2);
    assert!(serde_yaml::from_str::<InterfaceRule>("gauss").is_err());
}

/// EL-1 (frame): on the 1:1.4 face e_s·e_up > 0, e_a ∥ dam axis, e_n into the dam; in the
/// seed's axes the frame is the spec's, e_a = +Z; in the project axes e_a = −y.
#[test]
fn el1_frame_on_the_slope_face() {
    let x = slope_rectangle(2.0, 3.0);
    let n_ref: [f64; 3] = into_dam().into();
    for rule in RULES {
        let g = Interface8Geometry::new(&x, &n_ref, &FrameAxes::default(), rule).expect("valid");
        for f in &g.frames {
            assert!((f.s - slope_dir()).amax() < 1e-15, "{:?}", f.s);
            assert!((f.n - into_dam()).amax() < 1e-15);
            assert!((f.a + Vector3::y()).amax() < 1e-15);
        }
        assert!((g.area() - 6.0).abs() < 1e-14);
    }
    let f = Interface8Geometry::new(&x, &n_ref, &FrameAxes::default(), InterfaceRule::NewtonCotes)
        .expect("valid")
        .frames[0];
    println!(
        "EL-1 frame, project axes: e_s = {:.6?}, e_a = {:.6?}, e_n = {:.6?}; e_s.e_z = {:.6}, |e_a.e_y| = {}",
        f.s.as_slice(),
        f.a.as_slice(),
        f.n.as_slice(),
        f.s.z,
        f.a.y.abs()
    );
    // The same face in the seed's axes (X stream, Y up, Z dam axis): (x, y, z) → (X, Z, Y).
    let seed: Coords8 = x.map(|p| [p[0], p[2], p[1]]);
    let axes = FrameAxes::new([0.0, 0.0, 1.0], [0.0, 1.0, 0.0]).expect("valid");
    let g =
        Interface8Geometry::new(&seed, &[1.0, -1.4, 0.0], &axes, InterfaceRule::NewtonCotes).expect("valid");
    let r = 2.96f64.sqrt();
    for f in &g.frames {
        assert!((f.s - Vector3::new(1.4, 1.0, 0.0) / r).amax() < 1e-15);
        assert!((f.a - Vector3::z()).amax() < 1e-15);
        assert!((f.n - Vector3::new(1.0, -1.4, 0.0) / r).amax() < 1e-15);
    }
    println!(
        "EL-1 frame, seed axes: e_s = {:.6?}, e_a = {:.6?}, e_n = {:.6?}",
        g.frames[0].s.as_slice(),
        g.frames[0].a.as_slice(),
        g.frames[0].n.as_slice()
    );
    // Reversing n_ref reverses e_n and e_a and keeps e_s up-slope.
    let flipped = Interface8Geometry::new(
        &x,
        &(-into_dam()).into(),
        &FrameAxes::default(),
        InterfaceRule::NewtonCotes,
    )
    .expect("valid");
    assert!((flipped.frames[0].n + into_dam()).amax() < 1e-15);
    assert!((flipped.frames[0].a - Vector3::y()).amax() < 1e-15);
    assert!((flipped.frames[0].s - slope_dir()).amax() < 1e-15);
}

/// EL-1 (rigid motion): rigid translations and rotations of both faces give δ = 0, zero forces,
/// and K annihilates the six rigid modes, on a warped element with either rule.
#[test]
fn el1_rigid_motion_gives_no_jump_and_no_force() {
    let x = warped();
    for rule in RULES {
        let g = Interface8Geometry::new(&x, &[0.3, 0.2, 1.0], &FrameAxes::default(), rule).expect("valid");
        let mut worst_jump = 0.0f64;
        let mut worst_force = 0.0f64;
        let mut worst_ku = 0.0f64;
        let k = g.stiffness(&[nonsym_d(); 4]);
        for (t, w) in [
            (Vector3::new(0.3, -0.2, 0.5), Vector3::zeros()),
            (Vector3::zeros(), Vector3::new(1e-3, -2e-3, 0.5e-3)),
            (
                Vector3::new(0.01, 0.02, -0.03),
                Vector3::new(-0.7e-3, 0.2e-3, 1.3e-3),
            ),
        ] {
            let u = rigid(&x, t, w);
            let resp = g.evaluate(&u, cubic_law).expect("law");
            for p in &resp.points {
                worst_jump = worst_jump.max(p.jump.amax());
            }
            worst_force = worst_force.max(resp.f_int.amax());
            worst_ku = worst_ku.max((k * u).amax() / (k.amax() * u.amax()));
        }
        println!("EL-1 rigid, {rule:?}: max |delta| = {worst_jump:e} m, max |f| = {worst_force:e} N, max |K u|/(|K||u|) = {worst_ku:e}");
        assert_eq!(worst_jump, 0.0);
        assert_eq!(worst_force, 0.0);
        assert!(worst_ku < 1e-15);
    }
}

/// EL-1 (uniform jump): a uniform relative displacement gives uniform tractions and nodal forces
/// equal to traction × tributary area (A/4 on a rectangle with either rule; on a planar
/// trapezoid ‖g1 × g2‖ at the node with the nodal rule and ∫N_a dA with Gauss), to 1e-12.
#[test]
fn el1_uniform_jump_gives_traction_times_tributary_area() {
    let d = nonsym_d();
    let jump_global = Vector3::new(2e-3, -1e-3, -3e-5);
    let u = uniform_jump(Vector3::new(0.1, 0.2, -0.3), jump_global);
    let law = |_: usize, j: &Local3, _: &LocalFrame| Ok::<_, Infallible>((d * j, d));
    // Rectangle on the slope: every node pair carries T A/4.
    let x = slope_rectangle(2.0, 3.0);
    for rule in RULES {
        let g = Interface8Geometry::new(&x, &into_dam().into(), &FrameAxes::default(), rule).expect("ok");
        let resp = g.evaluate(&u, law).expect("law");
        let t = resp.points[0].traction;
        let expect_t = d * g.frames[0].to_local(&jump_global);
        let mut err = (t - expect_t).amax() / expect_t.amax();
        for p in &resp.points {
            err = err.max((p.traction - t).amax() / t.amax());
        }
        let nodal = g.frames[0].to_global(&t) * (6.0 / 4.0);
        for a in 0..4 {
            let fa = resp.f_int.fixed_rows::<3>(3 * (a + 4)).into_owned();
            let fb = resp.f_int.fixed_rows::<3>(3 * a).into_owned();
            err = err.max((fa - nodal).amax() / nodal.amax());
            err = err.max((fb + nodal).amax() / nodal.amax());
        }
        println!("EL-1 uniform jump, rectangle 2x3 m on 1:1.4, {rule:?}: T = {:?} Pa, pair force = {:?} N, max rel error {err:.2e}", t.as_slice(), nodal.as_slice());
        assert!(err < 1e-12);
    }
    // Planar trapezoid, tilted: nodal rule ↔ ‖g1 × g2‖ at the nodes, Gauss ↔ ∫ N_a dA.
    let rot = nalgebra::Rotation3::from_euler_angles(-0.3, 0.5, 0.2);
    let face = [[0.0, 0.0], [3.0, 0.0], [2.0, 1.5], [0.5, 1.5]].map(|p| rot * Vector3::new(p[0], p[1], 0.0));
    let area_exact = 0.5 * (3.0 + 1.5) * 1.5;
    let x = zero_thickness(face);
    let n_ref: [f64; 3] = (rot * Vector3::z()).into();
    // Consistent tributary areas ∫ N_a dA by the 3×3 Gauss rule (exact: degree 2 per variable).
    let mut tributary = [0.0; 4];
    for p in HEX_GAUSS_3X3X3.iter().filter(|p| p.xi[2] == 0.0) {
        let st = [p.xi[0], p.xi[1]];
        let (g1, g2, _) = mid_surface(&face, &st);
        let w = p.weight / (8.0 / 9.0);
        let n = quad4_shape(&st);
        for a in 0..4 {
            tributary[a] += n[a] * g1.cross(&g2).norm() * w;
        }
    }
    assert!((tributary.iter().sum::<f64>() - area_exact).abs() < 1e-14);
    for rule in RULES {
        let g = Interface8Geometry::new(&x, &n_ref, &FrameAxes::default(), rule).expect("ok");
        let resp = g.evaluate(&u, law).expect("law");
        let tg = g.frames[0].to_global(&resp.points[0].traction);
        let areas: [f64; 4] = match rule {
            InterfaceRule::NewtonCotes => g.area_w,
            InterfaceRule::Gauss2x2 => tributary,
        };
        let mut err = (g.area() - area_exact).abs() / area_exact;
        let mut total = Vector3::zeros();
        for a in 0..4 {
            let fa = resp.f_int.fixed_rows::<3>(3 * (a + 4)).into_owned();
            err = err.max((fa - tg * areas[a]).amax() / (tg.amax() * area_exact));
            total += fa;
        }
        err = err.max((total - tg * area_exact).amax() / (tg.amax() * area_exact));
        println!(
            "EL-1 uniform jump, planar trapezoid, {rule:?}: tributary areas {areas:.6?} m2 (sum {:.6}), max rel error {err:.2e}",
            areas.iter().sum::<f64>()
        );
        assert!(err < 1e-12);
    }
}

/// The kernel's K is the exact derivative of its f_int: central differences with a nonlinear
/// law of known tangent on a warped, arbitrarily oriented element, both rules.
#[test]
fn tangent_matches_central_differences_with_an_exact_law() {
    let x = warped();
    let u0 = Vector24::from_fn(|i, _| ((i * 7 + 3) % 11) as f64 * 1e-4 - 5e-4);
    for rule in RULES {
        let g = Interface8Geometry::new(&x, &[0.3, 0.2, 1.0], &FrameAxes::default(), rule).expect("valid");
        let k = g.evaluate(&u0, cubic_law).expect("law").k;
        let k_fd = fd_jacobian(&u0, 1e-8, |u| g.evaluate(u, cubic_law).expect("law").f_int);
        let err = (k - k_fd).amax() / k_fd.amax();
        println!("kernel FD check, warped element, {rule:?}: max |K - K_fd|/max|K_fd| = {err:.2e}");
        assert!(err < 1e-7);
        // The per-point frames of a warped element differ.
        let spread = (g.frames[0].n - g.frames[2].n).norm();
        assert!(
            spread > 1e-2,
            "warped element should have varying normals ({spread})"
        );
    }
}

/// One committed state per point, then the element tangent for the step increment `u` against
/// central differences of the element residual, for model `m`. Returns the errors of
/// [`local_errors`].
fn model_fd_errors<M: InterfaceModel>(
    m: &M,
    committed: &[M::State; 4],
    g: &Interface8Geometry,
    u: &Vector24,
    h: [f64; 3],
) -> [f64; 4] {
    let law = |q: usize, d: &Local3, _: &LocalFrame| {
        m.update(&committed[q], d)
            .map(|up| (M::traction(&up.state), up.tangent))
    };
    let k = g.evaluate(u, law).expect("update").k;
    let k_fd = fd_jacobian_local(u, &g.frames[0], h, |v| g.evaluate(v, law).expect("update").f_int);
    local_errors(&k, &k_fd, &g.frames[0])
}

/// Element displacement giving the local jump `jumps[a]` at node pair `a` (face B fixed).
fn pair_jumps(f: &LocalFrame, jumps: [[f64; 3]; 4]) -> Vector24 {
    let mut u = Vector24::zeros();
    for a in 0..4 {
        let v = f.to_global(&Local3::from(jumps[a]));
        u.fixed_rows_mut::<3>(3 * (a + 4)).copy_from(&v);
    }
    u
}

/// A 1 m × 1 m element on the 1:1.4 upstream slope, nodal rule, normal into the dam.
fn unit_slope_element() -> Interface8Geometry {
    Interface8Geometry::new(
        &slope_rectangle(1.0, 1.0),
        &into_dam().into(),
        &FrameAxes::default(),
        InterfaceRule::NewtonCotes,
    )
    .expect("valid")
}

/// The element tangent against central differences of the element residual, for every law,
/// on the 1:1.4 slope element with a different state and jump at each point.
#[test]
fn element_tangent_matches_central_differences_for_every_law() {
    let g = unit_slope_element();
    let f = g.frames[0];
    let mut report = Vec::new();
    let max = |e: &[f64; 4]| e.iter().copied().fold(0.0, f64::max);

    // Mohr–Coulomb (consistent tangent, spec §8.3): two points sticking, two slipping.
    let mc = MohrCoulombInterface::new(&MohrCoulombParams::default());
    let s0 = mc.init_state(1e5).expect("init");
    let committed: [_; 4] = std::array::from_fn(|q| {
        mc.update(&s0, &Local3::new(5e-3 * q as f64, 2e-3, -1e-6))
            .expect("pre")
            .state
    });
    let u = pair_jumps(
        &f,
        [
            [2e-3, 1e-3, -2e-6],
            [30e-3, 5e-3, -1e-6],
            [40e-3, -20e-3, -3e-6],
            [1e-3, 0.0, 0.0],
        ],
    );
    let e = model_fd_errors(&mc, &committed, &g, &u, [1e-7, 1e-7, 1e-10]);
    report.push(("mohr_coulomb (consistent)", e));
    assert!(max(&e) < 1e-6, "MC: {e:?}");

    // Joint (exact piecewise-linear law), away from δ_n = 0: pairs closed and open.
    let jt = JointLaw::new(&JointParams::default());
    let committed = [jt.init_state(2e5).expect("init"); 4];
    let u = pair_jumps(
        &f,
        [
            [1e-3, 2e-3, -1e-6],
            [-3e-3, 1e-3, 2e-3],
            [0.0, 1e-3, -1e-5],
            [5e-3, -5e-3, 1e-4],
        ],
    );
    // Steps 1e-6 m (shear), 1e-8 m (normal): the law is linear on each side of δ_n = 0 and
    // every pair is ≥ 1e-6 m away from it, so large steps only lower the round-off.
    let e = model_fd_errors(&jt, &committed, &g, &u, [1e-6, 1e-6, 1e-8]);
    report.push(("joint (exact)", e));
    assert!(max(&e) < 1e-8, "joint: {e:?}");

    // GP interface with its numerical consistent tangent (spec §8.5), plastic loading.
    let params = GpInterfaceParams {
        tangent: TangentChoice::Numerical,
        ..GpInterfaceParams::default()
    };
    let gp = GpInterface::new(params).expect("params");
    let s0 = gp.init_state(2e5).expect("init");
    let committed: [_; 4] = std::array::from_fn(|q| {
        gp.update(&s0, &Local3::new(1e-3 * q as f64, 0.5e-3, -1e-4))
            .expect("pre")
            .state
    });
    let u = pair_jumps(
        &f,
        [
            [2e-3, 0.0, -1e-4],
            [1.5e-3, 1e-3, -5e-5],
            [3e-3, -1e-3, 0.0],
            [1e-3, 2e-3, -2e-4],
        ],
    );
    let e = model_fd_errors(&gp, &committed, &g, &u, [1e-7, 1e-7, 1e-8]);
    report.push(("gp_interface (numerical consistent)", e));
    assert!(max(&e) < 1e-4, "GP: {e:?}");
    // The continuum tangent is not the derivative of the discrete update (reported only).
    let gpc = GpInterface::new(GpInterfaceParams::default()).expect("params");
    let e = model_fd_errors(&gpc, &committed, &g, &u, [1e-7, 1e-7, 1e-8]);
    report.push(("gp_interface (continuum; report only)", e));

    // Hyperbolic: its continuum tangent diag(k_st, k_st, k2) (spec (H6), §8.4) is the limit of
    // the FD derivative for small shear increments at constant σ_n. Committed primary states,
    // then a 1e-6 m shear step along τ. Its normal columns are not checked: (H6) omits the
    // shear–normal coupling, and a normal perturbation changes SL and hence the branch (H5).
    let hy = HyperbolicInterface::new(&HyperbolicParams::default());
    let s0 = hy.init_state(1e5).expect("init");
    let pre = |q: usize| Local3::new(5e-3 + 5e-3 * q as f64, 2e-3 * q as f64, 0.0);
    let committed: [_; 4] = std::array::from_fn(|q| hy.update(&s0, &pre(q)).expect("pre").state);
    let step: [[f64; 3]; 4] = std::array::from_fn(|q| {
        let d = pre(q) * (1e-6 / pre(q).norm());
        [d[0], d[1], 0.0]
    });
    let u = pair_jumps(&f, step);
    let e = model_fd_errors(&hy, &committed, &g, &u, [1e-9, 1e-9, 1e-12]);
    report.push(("hyperbolic (continuum; 1e-6 m step; sn not checked)", e));
    assert!(e[0] < 1e-3 && e[2] < 1e-3 && e[3] < 1e-3, "hyperbolic: {e:?}");

    for (name, e) in report {
        println!(
            "element K vs central FD, {name}: block errors ss {:.2e}, sn {:.2e}, ns {:.2e}, nn {:.2e}",
            e[0], e[1], e[2], e[3]
        );
    }
}

/// Isotropic elastic tangent (Pa).
fn elastic(e: f64, nu: f64) -> Tangent6 {
    Tangent6(crate::material::elastic::isotropic_stiffness(e, nu))
}

/// Normal tractions t_n (Pa) along the interface of the EL-2 model, sorted by x, on the row of
/// points nearest to y = 0: (x, t_n) pairs.
type Profile = Vec<(f64, f64)>;

/// The EL-2 model (see [`el2_model`]).
#[derive(Debug, Clone, Copy)]
struct El2Setup {
    /// Elements along x (each 1 m × 1 m in plan).
    nx: usize,
    /// Leading foundation elements that are stiff.
    n_stiff: usize,
    /// Young's modulus of the upper block (Pa).
    e_upper: f64,
    /// Thickness of the upper block (m).
    h_upper: f64,
}

/// EL-2 model: a lower block of `nx` × 1 × 1 hex8 (1 m cubes; the first `n_stiff` stiff, the
/// others soft) and an upper block of `nx` × 1 × 1 hex8, joined by `nx` interface elements
/// (face B = lower block, n_ref = +z) with the linear law diag(k_s, k_s, k_n), under a uniform
/// pressure `p` on the top. Base fixed, y fixed everywhere (plane strain).
/// Returns the traction profile and the total interface normal force.
fn el2_model(setup: El2Setup, rule: InterfaceRule, k_n: f64, p: f64) -> (Profile, Vec<f64>, f64) {
    let nx = setup.nx;
    let per_layer = (nx + 1) * 2;
    let lower = |i: usize, j: usize, k: usize| i + (nx + 1) * j + per_layer * k;
    let upper = |i: usize, j: usize, k: usize| 2 * per_layer + lower(i, j, k);
    let mut coords = vec![[0.0; 3]; 4 * per_layer];
    for k in 0..2 {
        for j in 0..2 {
            for i in 0..=nx {
                coords[lower(i, j, k)] = [i as f64, j as f64, k as f64];
                coords[upper(i, j, k)] = [i as f64, j as f64, 1.0 + setup.h_upper * k as f64];
            }
        }
    }
    let ndof = 3 * coords.len();
    let mut kg = DMatrix::<f64>::zeros(ndof, ndof);
    let mut fg = DVector::<f64>::zeros(ndof);
    let scatter =
        |conn: &[usize; 8], ke: &Matrix24, fe: &Vector24, kg: &mut DMatrix<f64>, fg: &mut DVector<f64>| {
            for (a, &na) in conn.iter().enumerate() {
                for i in 0..3 {
                    fg[3 * na + i] += fe[3 * a + i];
                    for (b, &nb) in conn.iter().enumerate() {
                        for j in 0..3 {
                            kg[(3 * na + i, 3 * nb + j)] += ke[(3 * a + i, 3 * b + j)];
                        }
                    }
                }
            }
        };
    let hex = |n: &dyn Fn(usize, usize, usize) -> usize, i: usize| -> [usize; 8] {
        [
            n(i, 0, 0),
            n(i + 1, 0, 0),
            n(i + 1, 1, 0),
            n(i, 1, 0),
            n(i, 0, 1),
            n(i + 1, 0, 1),
            n(i + 1, 1, 1),
            n(i, 1, 1),
        ]
    };
    let (stiff, soft) = (elastic(25.5e9, 0.167), elastic(50e6, 0.25));
    let top = elastic(setup.e_upper, 0.2);
    for i in 0..nx {
        for (conn, d, loaded) in [
            (
                hex(&lower, i),
                if i < setup.n_stiff { stiff } else { soft },
                false,
            ),
            (hex(&upper, i), top, true),
        ] {
            let x: Coords8 = conn.map(|n| coords[n]);
            let ke = Hex8Geometry::new(&x).expect("valid hex").stiffness(&[d; 8]);
            let fe = if loaded {
                face_pressure_load(&x, 5, &[p; 4])
            } else {
                Vector24::zeros()
            };
            scatter(&conn, &ke, &fe, &mut kg, &mut fg);
        }
    }
    let d_int = Matrix3::from_diagonal(&Vector3::new(1e7, 1e7, k_n));
    let mut interfaces = Vec::new();
    for i in 0..nx {
        let conn = [
            lower(i, 0, 1),
            lower(i + 1, 0, 1),
            lower(i + 1, 1, 1),
            lower(i, 1, 1),
            upper(i, 0, 0),
            upper(i + 1, 0, 0),
            upper(i + 1, 1, 0),
            upper(i, 1, 0),
        ];
        let x: Coords8 = conn.map(|n| coords[n]);
        let g = Interface8Geometry::new(&x, &[0.0, 0.0, 1.0], &FrameAxes::default(), rule).expect("valid");
        let ke = g.stiffness(&[d_int; 4]);
        scatter(&conn, &ke, &Vector24::zeros(), &mut kg, &mut fg);
        interfaces.push((conn, g));
    }
    // Dirichlet conditions u = 0: base nodes (all DOFs) and every y DOF.
    let fixed: Vec<usize> = (0..ndof)
        .filter(|&dof| {
            let node = dof / 3;
            dof % 3 == 1 || (node < 2 * per_layer && coords[node][2] == 0.0)
        })
        .collect();
    for &dof in &fixed {
        kg.row_mut(dof).fill(0.0);
        kg.column_mut(dof).fill(0.0);
        kg[(dof, dof)] = 1.0;
        fg[dof] = 0.0;
    }
    let u = kg.lu().solve(&fg).expect("non-singular system");
    let mut profile = Vec::new();
    let mut total = 0.0;
    // Nodal tractions k_n·δ_n at the node pairs of the y = 0 row (the same from both sides).
    let mut nodal = vec![0.0; nx + 1];
    for (conn, _) in &interfaces {
        for a in [0usize, 1] {
            let i = conn[a] % (nx + 1);
            nodal[i] = k_n * (u[3 * conn[a + 4] + 2] - u[3 * conn[a] + 2]);
        }
    }
    for (conn, g) in &interfaces {
        let ue = Vector24::from_fn(|r, _| u[3 * conn[r / 3] + r % 3]);
        let jumps = g.jumps(&ue);
        for q in 0..4 {
            let t = d_int * jumps[q];
            total += t[2] * g.area_w[q];
            if g.positions[q][1] < 0.5 {
                profile.push((g.positions[q][0], t[2]));
            }
        }
    }
    profile.sort_by(|a, b| a.0.total_cmp(&b.0));
    profile.dedup_by(|a, b| (a.0 - b.0).abs() < 1e-12 && (a.1 - b.1).abs() <= 1e-9 * b.1.abs());
    (profile, nodal, total)
}

/// Largest deviation of a sampled profile from the straight line through each sample's two
/// neighbours, over the samples with `lo < x ≤ hi` (interior samples only), in units of `p`.
fn oscillation_amplitude(profile: &Profile, lo: f64, hi: f64, p: f64) -> f64 {
    let pts: Vec<(f64, f64)> = profile
        .iter()
        .copied()
        .filter(|(x, _)| *x > lo && *x <= hi)
        .collect();
    pts.windows(3)
        .map(|w| {
            let r = (w[1].0 - w[0].0) / (w[2].0 - w[0].0);
            (w[1].1 - (w[0].1 + r * (w[2].1 - w[0].1))).abs() / p
        })
        .fold(0.0, f64::max)
}

/// EL-2 (Day & Potts type, spec §5.4): a stiff slab (E = 25.5 GPa, 0.5 m) on an interface with
/// k_n = 10⁷ kPa/m over a foundation of 8 one-metre elements, the first two stiff (a plinth,
/// E = 25.5 GPa) and the others soft (E = 50 MPa), under a uniform 100 kPa load. Next to the
/// stiff block (2 m < x ≤ 5 m) the Gauss 2×2 tractions zig-zag and turn tensile, while the
/// nodal rule gives a smooth compressive profile; with a soft interface (k_n = 10⁵ kPa/m) the
/// Gauss oscillation mostly disappears. Both rules carry the whole load.
///
/// The amplitude is the largest deviation of a traction sample from the line through its two
/// neighbours, in units of the load. (8 elements instead of 4: a single soft element next to
/// the block gives too few samples to see a profile.)
#[test]
fn el2_gauss_oscillates_next_to_a_stiff_block_newton_cotes_does_not() {
    let p = 1e5;
    let setup = El2Setup {
        nx: 8,
        n_stiff: 2,
        e_upper: 25.5e9,
        h_upper: 0.5,
    };
    let (lo, hi) = (2.0, 5.0);
    let mut amp = std::collections::HashMap::new();
    for k_n in [1e8, 1e10, 1e12] {
        for rule in RULES {
            let (profile, nodal, total) = el2_model(setup, rule, k_n, p);
            let a = oscillation_amplitude(&profile, lo, hi, p);
            let near: Vec<f64> = profile
                .iter()
                .filter(|(x, _)| *x >= lo && *x <= hi)
                .map(|v| v.1)
                .collect();
            let tensile = near.iter().filter(|&&t| t > 0.0).count();
            println!(
                "EL-2 {rule:?}, k_n = {k_n:.0e} Pa/m: total normal force {total:.6e} N (load {:.6e} N); amplitude on ({lo}, {hi}] m = {a:.4} p; tensile points on [{lo}, {hi}] m: {tensile}",
                -8.0 * p
            );
            println!(
                "    points (x m: t_n kPa) {}",
                profile
                    .iter()
                    .map(|(x, t)| format!("{x:.2}: {:.1}", t / 1e3))
                    .collect::<Vec<_>>()
                    .join(", ")
            );
            println!(
                "    node pairs k_n*delta_n (kPa) {}",
                nodal
                    .iter()
                    .map(|t| format!("{:.1}", t / 1e3))
                    .collect::<Vec<_>>()
                    .join(", ")
            );
            assert!((total + 8.0 * p).abs() < 1e-8 * 8.0 * p, "equilibrium: {total}");
            amp.insert((rule, k_n as i64), (a, tensile));
        }
    }
    let nc = amp[&(InterfaceRule::NewtonCotes, 10_000_000_000)];
    let gauss = amp[&(InterfaceRule::Gauss2x2, 10_000_000_000)];
    let gauss_soft = amp[&(InterfaceRule::Gauss2x2, 100_000_000)];
    assert!(
        nc.0 < 0.05 && nc.1 == 0,
        "Newton-Cotes should be smooth and compressive: {nc:?}"
    );
    assert!(
        gauss.0 > 0.5 && gauss.1 > 0,
        "Gauss should oscillate into tension: {gauss:?}"
    );
    assert!(gauss.0 > 10.0 * nc.0, "Gauss {gauss:?} vs Newton-Cotes {nc:?}");
    assert!(
        gauss_soft.0 < 0.5 * gauss.0,
        "softer interface, smaller oscillation: {gauss_soft:?}"
    );
}

/// EL-3 (thin-layer scaling, spec §9.5): for the GP interface the element stiffness scales as
/// 1/t. In the GP law t enters through the strain ε = S·δ/t and the tangent dT/dδ = S·D·S/t
/// (spec (E6), (E7)); D depends on the state (σ, e) only under the literal reading
/// `stiffness_basis = strain`, so there, at the same state, doubling t halves K exactly, and a
/// displacement path scaled with t reaches the same state (same strains, same tractions) with
/// half the stiffness. Under the default `stiffness_basis = displacement` (D_s0, D_n0, H0 per
/// unit displacement, D_strain = t·D) the t factors cancel: K does not depend on t at the same
/// state.
#[test]
fn el3_gp_interface_stiffness_scales_with_one_over_t() {
    let g = unit_slope_element();
    let f = g.frames[0];
    let run = |basis: StiffnessBasis, t: f64, scale: f64| {
        let gp = GpInterface::new(GpInterfaceParams {
            t,
            stiffness_basis: basis,
            normal_basis: basis,
            ..GpInterfaceParams::default()
        })
        .expect("params");
        let s0 = gp.init_state(1e5).expect("init");
        let committed: [_; 4] = std::array::from_fn(|_| s0.clone());
        let law = |q: usize, d: &Local3, _: &LocalFrame| {
            gp.update(&committed[q], d)
                .map(|up| (GpInterface::traction(&up.state), up.tangent))
        };
        let at_rest = g.evaluate(&Vector24::zeros(), law).expect("update");
        // Plastic step: shear 2 mm and 1 mm, closure 0.1 mm per 0.1 m of thickness.
        let u = pair_jumps(
            &f,
            [
                [2e-3, 1e-3, -1e-4],
                [2e-3, 1e-3, -1e-4],
                [1.5e-3, 0.5e-3, -0.5e-4],
                [2.5e-3, 0.0, -1e-4],
            ],
        ) * scale;
        let loaded = g.evaluate(&u, law).expect("update");
        (at_rest, loaded)
    };
    let (rest1, load1) = run(StiffnessBasis::Strain, 0.1, 1.0);
    let (rest2, load2) = run(StiffnessBasis::Strain, 0.2, 2.0);
    let rest_ratio = (rest2.k * 2.0 - rest1.k).amax() / rest1.k.amax();
    let load_ratio = (load2.k * 2.0 - load1.k).amax() / load1.k.amax();
    let force_diff = (load2.f_int - load1.f_int).amax() / load1.f_int.amax();
    let kk = |r: &InterfaceResponse, a: usize, c: usize| {
        let q = local_rotation(&f);
        (q * r.k * q.transpose())[(3 * a + c, 3 * a + c)]
    };
    println!(
        "EL-3 strain basis: pair 4 local K_ss, K_nn at rest: t = 0.1 m {:.6e}, {:.6e} N/m; t = 0.2 m {:.6e}, {:.6e} N/m",
        kk(&rest1, 4, 0),
        kk(&rest1, 4, 2),
        kk(&rest2, 4, 0),
        kk(&rest2, 4, 2)
    );
    println!(
        "EL-3 strain basis: max |2 K(0.2) - K(0.1)|/max|K(0.1)| at rest {rest_ratio:.2e}, after the scaled plastic step {load_ratio:.2e}; f_int difference {force_diff:.2e}; tractions at pair 0: {:?} vs {:?} Pa",
        load1.points[0].traction.as_slice(),
        load2.points[0].traction.as_slice()
    );
    assert!(rest_ratio < 1e-12 && load_ratio < 1e-12 && force_diff < 1e-12);
    // The plastic step did leave the elastic state (the tangent is not the at-rest one).
    assert!((load1.k - rest1.k).amax() > 1e-3 * rest1.k.amax());
    let (rest1, _) = run(StiffnessBasis::Displacement, 0.1, 1.0);
    let (rest2, _) = run(StiffnessBasis::Displacement, 0.2, 2.0);
    let same = (rest2.k - rest1.k).amax() / rest1.k.amax();
    println!(
        "EL-3 displacement basis (default): K_ss at rest t = 0.1 m {:.6e}, t = 0.2 m {:.6e} N/m; max |K(0.2) - K(0.1)|/max|K(0.1)| = {same:.2e}",
        kk(&rest1, 4, 0),
        kk(&rest2, 4, 0)
    );
    assert!(same < 1e-12);
}

/// A vertical joint between two slabs of the 1:1.4 face: the joint plane holds the slope line
/// and the slab normal (2 m × 0.5 m), its normal is the dam axis y (face B → face A along +y).
fn vertical_joint() -> (Interface8Geometry, LocalFrame) {
    let o = Vector3::new(3.0, 2.0, 1.0);
    let (s, t) = (slope_dir() * 2.0, into_dam() * 0.5);
    let x = zero_thickness([o, o + s, o + s + t, o + t]);
    let axes = FrameAxes::new([0.0, 1.0, 0.0], slope_dir().into()).expect("orthogonal");
    let g = Interface8Geometry::new(&x, &[0.0, 1.0, 0.0], &axes, InterfaceRule::NewtonCotes).expect("valid");
    (g, g.frames[0])
}

/// With the slab's up-slope line as "up", a vertical joint gets §6.1's frame: e_s = up-slope
/// (e_1), e_a = slab normal (e_2), e_n = dam axis.
#[test]
fn joint_frame_follows_the_slab_slope() {
    let (g, f) = vertical_joint();
    println!(
        "vertical joint frame: e_s = {:?}, e_a = {:?}, e_n = {:?}",
        f.s.as_slice(),
        f.a.as_slice(),
        f.n.as_slice()
    );
    assert!((f.s - slope_dir()).amax() < 1e-15);
    assert!((f.a - into_dam()).amax() < 1e-15);
    assert!((f.n - Vector3::y()).amax() < 1e-15);
    assert!((g.area() - 1.0).abs() < 1e-14);
    // With the default axes the fallback takes the vertical instead of the slope line.
    let x: Coords8 = std::array::from_fn(|a| g.positions[a % 4]);
    let d = Interface8Geometry::new(
        &x,
        &[0.0, 1.0, 0.0],
        &FrameAxes::default(),
        InterfaceRule::NewtonCotes,
    )
    .expect("valid");
    println!(
        "vertical joint, default axes: e_s = {:?}, e_a = {:?}",
        d.frames[0].s.as_slice(),
        d.frames[0].a.as_slice()
    );
    assert!((d.frames[0].s - Vector3::z()).amax() < 1e-15);
}

/// Normal force on face A (N, along e_n) and the normal stiffness of one pair for a uniform
/// local jump of face A relative to face B, with the joint law from its stress-free state.
fn joint_uniform(g: &Interface8Geometry, f: &LocalFrame, jump: Local3) -> InterfaceResponse {
    let jt = JointLaw::new(&JointParams::default());
    let s0 = jt.init_state(0.0).expect("init");
    let u = uniform_jump(Vector3::zeros(), f.to_global(&jump));
    g.evaluate(&u, |_, d: &Local3, _: &LocalFrame| {
        jt.update(&s0, d)
            .map(|up| (JointLaw::traction(&up.state), up.tangent))
    })
    .expect("update")
}

/// JT-1 (spec §6.1, §9.5): joint element in compression (k_c) and opening (k_t), exact pair
/// forces, nodal forces continuous at δ_n = 0, each pair on its own branch with the nodal rule,
/// and a Newton iteration on the normal load crossing δ_n = 0 without chattering.
#[test]
fn jt1_joint_element_compression_opening_and_continuity() {
    let (g, f) = vertical_joint();
    let pair_area = 0.25;
    let (kc, kt) = (2.5e10, 5e6);
    for (dn, k) in [(-1e-4, kc), (1e-3, kt)] {
        let r = joint_uniform(&g, &f, Local3::new(0.0, 0.0, dn));
        let q = local_rotation(&f);
        let kl = q * r.k * q.transpose();
        let mut err = 0.0f64;
        for a in 0..4 {
            let fa = f.to_local(&r.f_int.fixed_rows::<3>(3 * (a + 4)).into_owned());
            err =
                err.max((fa - Local3::new(0.0, 0.0, k * dn * pair_area)).amax() / (k * dn.abs() * pair_area));
            err = err.max((kl[(3 * a + 2, 3 * a + 2)] - k * pair_area).abs() / (k * pair_area));
        }
        println!(
            "JT-1 delta_n = {dn:+e} m: pair normal force {:.6e} N, pair K_nn {:.6e} N/m, max rel error {err:.1e}",
            f.to_local(&r.f_int.fixed_rows::<3>(12).into_owned())[2],
            kl[(14, 14)]
        );
        assert!(err < 1e-12);
    }
    for h in [1e-9, 1e-12, 1e-15] {
        let fp = joint_uniform(&g, &f, Local3::new(0.0, 0.0, h)).f_int;
        let fm = joint_uniform(&g, &f, Local3::new(0.0, 0.0, -h)).f_int;
        let jump = (fp - fm).amax();
        let bound = (kc + kt) * h * pair_area;
        println!("JT-1 continuity: max |f(+{h:e}) - f(-{h:e})| = {jump:.3e} N (bound (k_c + k_t) h A/4 = {bound:.3e} N)");
        assert!(jump <= bound * (1.0 + 1e-12));
    }
    // Rotation about the joint's slope line: pairs 0, 1 open, pairs 2, 3 close; with the nodal
    // rule each pair carries exactly its own branch.
    let jt = JointLaw::new(&JointParams::default());
    let s0 = jt.init_state(0.0).expect("init");
    let dn = [2e-4, 2e-4, -1e-4, -1e-4];
    let u = pair_jumps(&f, std::array::from_fn(|a| [0.0, 0.0, dn[a]]));
    let r = g
        .evaluate(&u, |_, d: &Local3, _: &LocalFrame| {
            jt.update(&s0, d)
                .map(|up| (JointLaw::traction(&up.state), up.tangent))
        })
        .expect("update");
    for a in 0..4 {
        let fa = f.to_local(&r.f_int.fixed_rows::<3>(3 * (a + 4)).into_owned())[2];
        let k = if dn[a] > 0.0 { kt } else { kc };
        println!(
            "JT-1 mixed: pair {a} delta_n = {:+e} m, normal force {fa:.6e} N",
            dn[a]
        );
        assert!((fa - k * dn[a] * pair_area).abs() <= 1e-12 * k * dn[a].abs() * pair_area);
    }
    // Newton on the normal translation w of face A for a total normal force F (N) crossing 0.
    let mut w = 0.0;
    for target in [2e3, -5e5, 1e3, -1.0, 0.5, -1e6] {
        let mut iters = 0;
        loop {
            let r = joint_uniform(&g, &f, Local3::new(0.0, 0.0, w));
            let q = local_rotation(&f);
            let kl = q * r.k * q.transpose();
            let force: f64 = (4..8)
                .map(|a| f.to_local(&r.f_int.fixed_rows::<3>(3 * a).into_owned())[2])
                .sum();
            let residual = force - target;
            if residual.abs() <= 1e-8 * target.abs().max(1.0) {
                break;
            }
            let stiffness: f64 = (4..8)
                .map(|a| (4..8).map(|b| kl[(3 * a + 2, 3 * b + 2)]).sum::<f64>())
                .sum();
            w -= residual / stiffness;
            iters += 1;
            assert!(iters <= 3, "target {target} N: no convergence in 3 iterations");
        }
        println!("JT-1 Newton: total normal force {target:+e} N reached in {iters} iterations (delta_n = {w:+.6e} m)");
    }
}

/// JT-2 (spec §6.1, §9.5): combined opening and shear; the shear stiffness is 10³ kPa/m and the
/// shear forces are k_s·δ·A/4 per pair, whatever the opening.
#[test]
fn jt2_joint_element_shear_independent_of_opening() {
    let (g, f) = vertical_joint();
    let (ks, pair_area) = (1e6, 0.25);
    let q = local_rotation(&f);
    for dn in [-1e-4, 0.0, 1e-3, 0.05] {
        let jump = Local3::new(2e-3, -1e-3, dn);
        let r = joint_uniform(&g, &f, jump);
        let kl = q * r.k * q.transpose();
        let mut err = 0.0f64;
        for a in 0..4 {
            let fa = f.to_local(&r.f_int.fixed_rows::<3>(3 * (a + 4)).into_owned());
            for c in 0..2 {
                err = err.max((fa[c] - ks * jump[c] * pair_area).abs() / (ks * 2e-3 * pair_area));
                err = err.max((kl[(3 * a + c, 3 * a + c)] - ks * pair_area).abs() / (ks * pair_area));
            }
        }
        println!(
            "JT-2 delta_n = {dn:+e} m: pair shear forces {:.6e}, {:.6e} N, pair K_ss = {:.6e} N/m (k_s A/4 = {:.6e}), max rel error {err:.1e}",
            f.to_local(&r.f_int.fixed_rows::<3>(12).into_owned())[0],
            f.to_local(&r.f_int.fixed_rows::<3>(12).into_owned())[1],
            kl[(12, 12)],
            ks * pair_area
        );
        assert!(err < 1e-12);
    }
}

#[test]
fn invalid_geometry_is_rejected_with_its_reason() {
    let x = slope_rectangle(1.0, 1.0);
    let rule = InterfaceRule::NewtonCotes;
    let axes = FrameAxes::default();
    // n_ref in the plane of the face.
    let err = Interface8Geometry::new(&x, &slope_dir().into(), &axes, rule).expect_err("in plane");
    assert!(
        matches!(err, InterfaceGeometryError::ReferenceInPlane { .. }),
        "{err}"
    );
    assert!(Interface8Geometry::new(&x, &[f64::NAN, 0.0, 0.0], &axes, rule).is_err());
    // A collapsed edge: nodes 1 and 2 coincide (and their pairs).
    let mut c = x;
    c[2] = c[1];
    c[6] = c[5];
    let err = Interface8Geometry::new(&c, &into_dam().into(), &axes, rule).expect_err("collapsed");
    println!("collapsed edge: {err}");
    assert!(
        matches!(err, InterfaceGeometryError::Degenerate { point: 1 | 2, .. }),
        "{err}"
    );
    // All nodes at one point.
    let p = [[1.0, 2.0, 3.0]; 8];
    let err = Interface8Geometry::new(&p, &[0.0, 0.0, 1.0], &axes, rule).expect_err("point");
    assert!(
        matches!(err, InterfaceGeometryError::DegenerateCentre { .. }),
        "{err}"
    );
    // A concave ("arrowhead") quad: node 2 inside the triangle of nodes 0, 1, 3, so the normal
    // at node 2 opposes the centre normal.
    let arrow = zero_thickness(
        [[0.0, 0.0], [2.0, 0.0], [0.4, 0.4], [0.0, 2.0]].map(|p| Vector3::new(p[0], p[1], 0.0)),
    );
    let err = Interface8Geometry::new(&arrow, &[0.0, 0.0, 1.0], &axes, rule).expect_err("folded");
    println!("concave quad: {err}");
    assert_eq!(err, InterfaceGeometryError::Folded { point: 2 });
    // A bow-tie (nodes 2 and 3 swapped) has no area at its centre.
    let mut b = x;
    b.swap(2, 3);
    b.swap(6, 7);
    let err = Interface8Geometry::new(&b, &into_dam().into(), &axes, rule).expect_err("bow-tie");
    println!("bow-tie: {err}");
    assert!(
        matches!(err, InterfaceGeometryError::DegenerateCentre { .. }),
        "{err}"
    );
}
