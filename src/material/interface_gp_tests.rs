//! Tests of the GP interface (spec §9.2 IF-1 … IF-7, property tests, hard cases).
//!
//! Paths are driven by a small mixed-control driver: the shear jumps are imposed and the normal
//! jump is found by Newton so that σ_n = σ_ref + K·(δ_n − δ_n,ref) (K = 0: constant normal load,
//! CNL; K > 0: constant normal stiffness, CNS; spec §9.2).

use super::*;
use crate::material::interface_gp_functions::MAPPING_RATIO_CAP;
use proptest::prelude::*;
use std::time::Instant;

const KPA: f64 = 1e3;
const MM: f64 = 1e-3;

/// The readings before issue 19, with one basis for all three constants: `normal_basis` =
/// `stiffness_basis`, no void-ratio bound, `reversal_branch = start`. The G2.3 and G7 tables
/// of the module docs were measured with these (`displacement` was the default).
fn legacy_params(basis: StiffnessBasis) -> GpInterfaceParams {
    GpInterfaceParams {
        stiffness_basis: basis,
        normal_basis: basis,
        void_ratio_bound: VoidRatioBound::None,
        reversal_branch: ReversalBranch::Start,
        ..GpInterfaceParams::default()
    }
}

/// A legacy model (see [`legacy_params`]).
fn model(basis: StiffnessBasis) -> GpInterface {
    GpInterface::new(legacy_params(basis)).expect("seed parameters are valid")
}

/// The strain reading of the normal response (issue 19, option): `normal_basis: strain`,
/// `void_ratio_bound: smooth`, `reversal_branch: trial`, the other keys at their defaults
/// (seed Table 2).
fn strain_params() -> GpInterfaceParams {
    GpInterfaceParams {
        normal_basis: StiffnessBasis::Strain,
        void_ratio_bound: VoidRatioBound::Smooth,
        reversal_branch: ReversalBranch::Trial,
        ..GpInterfaceParams::default()
    }
}

/// The model of [`strain_params`].
fn strain_model() -> GpInterface {
    GpInterface::new(strain_params()).expect("seed parameters are valid")
}

fn model_with_reading(basis: StiffnessBasis, reading: ElasticVoidRatio) -> GpInterface {
    GpInterface::new(GpInterfaceParams {
        elastic_void_ratio: reading,
        ..legacy_params(basis)
    })
    .expect("seed parameters are valid")
}

/// Largest closure the void-ratio bound allows, (e0 − e_min)/(1 + e0)·t (m).
fn closure_bound(m: &GpInterface) -> f64 {
    let p = &m.params;
    (p.e0 - p.e_min) / (1.0 + p.e0) * p.t
}

/// Panics when a model with the smooth bound holds a state below e_min.
fn check_void_ratio(m: &GpInterface, st: &GpInterfaceState) {
    if m.params.void_ratio_bound != VoidRatioBound::None {
        assert!(
            st.void_ratio >= m.params.e_min,
            "e = {} below e_min = {}",
            st.void_ratio,
            m.params.e_min
        );
    }
}

/// Mixed-control driver (CNL / CNS).
struct Driver<'a> {
    m: &'a GpInterface,
    st: GpInterfaceState,
    k_cns: f64,
    sigma_ref: f64,
    dn_ref: f64,
    updates: u64,
    unresolved: u64,
}

impl<'a> Driver<'a> {
    fn new(m: &'a GpInterface, sigma_n: f64, k_cns: f64) -> Self {
        let st = m.init_state(sigma_n).expect("valid initial stress");
        Driver {
            m,
            st,
            k_cns,
            sigma_ref: sigma_n,
            dn_ref: 0.0,
            updates: 0,
            unresolved: 0,
        }
    }

    /// One step of shear jump increments with the normal jump solved for: Newton on δ_n with the
    /// returned tangent, safeguarded by bisection once a sign change is bracketed; to 1e-9.
    fn step(&mut self, dus: f64, dua: f64) -> Result<(), MaterialError> {
        let mut dn = 0.0;
        let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
        for it in 0..300 {
            let u = match self.m.update(&self.st, &Local3::new(dus, dua, dn)) {
                Ok(u) => u,
                Err(e) if e.to_string().contains("void-ratio bound") => {
                    // too much closure: back towards the committed closure
                    lo = lo.max(dn);
                    dn = if hi.is_finite() { 0.5 * (lo + hi) } else { 0.5 * dn };
                    continue;
                }
                Err(e) => return Err(e),
            };
            self.updates += 1;
            let target = self.sigma_ref + self.k_cns * (self.st.jump[2] + dn - self.dn_ref);
            let res = u.state.stress[2] - target;
            if res.abs() <= 1e-9 * target.abs().max(KPA) {
                self.accept(u.state);
                return Ok(());
            }
            // res decreases with δ_n (opening lowers σ_n, raises the CNS target).
            if res > 0.0 {
                lo = lo.max(dn);
            } else {
                hi = hi.min(dn);
            }
            let slope = -u.tangent[(2, 2)] - self.k_cns;
            let mut next = dn - res / slope;
            if lo.is_finite() && hi.is_finite() {
                if hi - lo < 1e-13 {
                    // σ_n(δ_n) jumps across the target at a reversal (spec G7: under stress
                    // control an exact solution may not exist there): take the closure side.
                    let state = self.m.update(&self.st, &Local3::new(dus, dua, lo))?.state;
                    self.accept(state);
                    self.unresolved += 1;
                    return Ok(());
                }
                if it >= 20 || !(next > lo && next < hi) {
                    next = 0.5 * (lo + hi);
                }
            }
            dn = next;
        }
        Err(MaterialError::new("driver: normal Newton did not converge"))
    }

    /// Commits a step's state; every state of a bounded model is checked against e_min.
    fn accept(&mut self, state: GpInterfaceState) {
        check_void_ratio(self.m, &state);
        self.st = state;
    }

    /// Normal-stress controlled step at zero shear increment (CNL target change).
    fn normal_to(&mut self, sigma: f64, steps: usize) -> Result<(), MaterialError> {
        let s0 = self.sigma_ref;
        for i in 1..=steps {
            self.sigma_ref = s0 + (sigma - s0) * i as f64 / steps as f64;
            self.step(0.0, 0.0)?;
        }
        Ok(())
    }

    fn tau(&self) -> f64 {
        (self.st.stress[0].powi(2) + self.st.stress[1].powi(2)).sqrt()
    }
}

/// Monotonic CNL shear record: (u, τ, v_mat) at each step.
fn cnl_monotonic(m: &GpInterface, sigma_n: f64, u_max: f64, du: f64) -> Vec<(f64, f64, f64)> {
    let mut d = Driver::new(m, sigma_n, 0.0);
    let mut out = vec![(0.0, 0.0, d.st.v_mat)];
    let n = (u_max / du).round() as usize;
    for i in 1..=n {
        d.step(du, 0.0).expect("CNL step");
        assert!((d.st.stress[2] - sigma_n).abs() <= 1e-6 * sigma_n, "σ_n held");
        out.push((i as f64 * du, d.st.stress[0], d.st.v_mat));
    }
    out
}

fn peak(rec: &[(f64, f64, f64)]) -> (f64, f64) {
    rec.iter()
        .fold((0.0, 0.0), |acc, r| if r.1 > acc.1 { (r.0, r.1) } else { acc })
}

/// First displacement at which τ reaches `frac`·τ_peak (linear interpolation).
fn u_at_fraction(rec: &[(f64, f64, f64)], frac: f64) -> f64 {
    let target = frac * peak(rec).1;
    for w in rec.windows(2) {
        if w[1].1 >= target {
            let f = (target - w[0].1) / (w[1].1 - w[0].1);
            return w[0].0 + f * (w[1].0 - w[0].0);
        }
    }
    f64::NAN
}

fn tau_at(rec: &[(f64, f64, f64)], u: f64) -> f64 {
    rec.iter()
        .min_by(|a, b| (a.0 - u).abs().total_cmp(&(b.0 - u).abs()))
        .map(|r| r.1)
        .unwrap_or(f64::NAN)
}

// ---------------------------------------------------------------------------------------------
// Parameters

#[test]
fn default_parameters_are_seed_table_2_in_si() {
    let p = strain_params();
    assert_eq!((p.ds0, p.dn0, p.h0), (1.0e6, 1.5e6, 8.5e6));
    assert_eq!((p.t, p.e0, p.mc, p.fh), (0.1, 0.25, 0.88, 2.0));
    // a, b in Pa^±0.5: Δe_c is unit-free, so a(kPa)·√1000 and b(kPa)/√1000.
    assert!((p.a / SQRT_1000 - 224.0).abs() < 1e-12);
    assert!((p.b * SQRT_1000 - 0.06).abs() < 1e-15);
    // Breakage limit 1/(ab) = 0.074 in both unit systems (spec §2.10).
    assert!((1.0 / (p.a * p.b) - 1.0 / (224.0 * 0.06)).abs() < 1e-14);
    p.validate().expect("seed parameters validate");
}

#[test]
fn invalid_parameters_name_the_field() {
    let bad = |f: fn(&mut GpInterfaceParams)| {
        let mut p = strain_params();
        f(&mut p);
        p.validate().expect_err("must fail").field
    };
    assert_eq!(bad(|p| p.t = 0.0), "t");
    assert_eq!(bad(|p| p.ds0 = -1.0), "Ds0");
    assert_eq!(bad(|p| p.h0 = f64::NAN), "H0");
    assert_eq!(bad(|p| p.e0 = 0.0), "e0");
    assert_eq!(bad(|p| p.sigma_open = 2e3), "sigma_open");
    assert_eq!(bad(|p| p.e_min = 0.25), "e_min");
    assert_eq!(bad(|p| p.e_min = -0.1), "e_min");
    // e_min is only read with the bound.
    let free = GpInterfaceParams {
        void_ratio_bound: VoidRatioBound::None,
        e_min: 1.0,
        ..strain_params()
    };
    free.validate().expect("e_min unused without the bound");
    assert_eq!(
        bad(|p| p.integration.max_substeps = 0),
        "integration.max_substeps"
    );
    assert!(GpInterface::new(GpInterfaceParams {
        mc: 0.0,
        ..strain_params()
    })
    .is_err());
}

#[test]
fn parameters_serde_keys_defaults_and_unknown_fields() {
    let p = strain_params();
    let json = serde_json::to_string(&p).expect("serialize");
    for key in [
        "\"Ds0\"",
        "\"Dn0\"",
        "\"H0\"",
        "\"Mc\"",
        "\"eGamma\"",
        "\"Mf\"",
        "\"stiffness_basis\"",
        "\"normal_basis\"",
        "\"void_ratio_bound\"",
        "\"e_min\"",
    ] {
        assert!(json.contains(key), "{key} in {json}");
    }
    let back: GpInterfaceParams = serde_json::from_str(&json).expect("deserialize");
    assert_eq!(back, p);
    // Optional keys fall back to the documented defaults.
    let minimal = r#"{"Ds0":1e6,"Dn0":1.5e6,"H0":8.5e6,"Mc":0.88,"eGamma":0.4,"lambda":0.091,
        "alpha":0.65,"rd":0.2,"km":0.6,"Mf":0.65,"k":0.5,"fh":2,"c":3,"c0":1e-4,
        "a":7083.5,"b":0.0019,"t":0.1,"fh_mode":"memory","stiffness_basis":"strain"}"#;
    let q: GpInterfaceParams = serde_json::from_str(minimal).expect("minimal input");
    assert_eq!((q.e0, q.sigma_min, q.pa, q.e_min), (0.25, 1e3, 101.3e3, 0.15));
    assert_eq!(
        (q.normal_basis, q.void_ratio_bound, q.reversal_branch),
        (
            StiffnessBasis::Displacement,
            VoidRatioBound::Bandis,
            ReversalBranch::Trial
        )
    );
    assert_eq!(
        (q.fh_mode, q.stiffness_basis, q.peak_form),
        (FhMode::Memory, StiffnessBasis::Strain, PeakForm::Exp)
    );
    let unknown = minimal.replace("\"t\":0.1", "\"t\":0.1,\"thickness\":0.1");
    assert!(serde_json::from_str::<GpInterfaceParams>(&unknown).is_err());
    let schema = serde_json::to_string(&schemars::schema_for!(GpInterfaceParams)).expect("schema");
    assert!(schema.contains("eGamma"));
}

// ---------------------------------------------------------------------------------------------
// Elasticity and signs

#[test]
fn elastic_moduli_eq_5_and_the_two_readings() {
    let lit = model(StiffnessBasis::Strain);
    let disp = model(StiffnessBasis::Displacement);
    let (ds, dn) = lit.elastic_moduli(100.0 * KPA, 0.0, 0.25);
    let expect = 1.0e6 * 5.0 * (100.0 / 101.3);
    assert!((ds - expect).abs() < 1e-9 * expect, "{ds} vs {expect}");
    assert!((dn / ds - 1.5).abs() < 1e-14);
    let (ds2, dn2) = disp.elastic_moduli(100.0 * KPA, 0.0, 0.25);
    assert!((ds2 / ds - 0.1).abs() < 1e-14, "displacement reading = t·literal");
    assert!(
        (dn2 / dn - 0.1).abs() < 1e-14,
        "legacy: both bases per displacement"
    );
    // Default: shear per displacement, normal per strain, D_n divided by the closure factor.
    let m = strain_model();
    let (ds3, dn3) = m.elastic_moduli(100.0 * KPA, 0.0, 0.25);
    assert!((ds3 - ds2).abs() < 1e-9 * ds2 && (dn3 - dn).abs() < 1e-9 * dn);
    let e = 0.16;
    let (_, dn4) = m.elastic_moduli(100.0 * KPA, 0.0, e);
    assert!((dn4 * m.closure_factor(e) - dn).abs() < 1e-9 * dn);
    assert!(dn4 > 4.0 * dn, "stiffening near e_min: {dn4} vs {dn}");
    // σ_min floor: finite, positive moduli at zero normal stress.
    let (ds0, _) = lit.elastic_moduli(0.0, 0.0, 0.25);
    assert!(ds0 > 0.0 && ds0.is_finite());
}

#[test]
fn traction_sign_and_tangent_scaling() {
    let m = strain_model();
    let st = m.init_state(200.0 * KPA).expect("init");
    let t = GpInterface::traction(&st);
    assert_eq!(t, Local3::new(0.0, 0.0, -200.0 * KPA));
    // Pure normal unloading (opening direction) from a virgin state is elastic: dT/dδ = S D S / t.
    let u = m.update(&st, &Local3::new(0.0, 0.0, 1e-7)).expect("update");
    assert_eq!(u.kind, TangentKind::Elastic);
    let (_, dn) = m.elastic_moduli(u.state.stress[2], 0.0, u.state.void_ratio);
    assert!((u.tangent[(2, 2)] - dn / m.params.t).abs() < 1e-9 * dn / m.params.t);
    assert!(u.state.stress[2] < 200.0 * KPA, "opening reduces σ_n");
    assert!(GpInterface::traction(&u.state)[2] > -200.0 * KPA);
}

// ---------------------------------------------------------------------------------------------
// IF-1 normal compression, unloading, reloading at τ = 0

#[test]
fn if1_normal_compression_unloading_reloading() {
    for (basis, reading) in [
        (StiffnessBasis::Displacement, ElasticVoidRatio::Initial),
        (StiffnessBasis::Strain, ElasticVoidRatio::Initial),
        (StiffnessBasis::Displacement, ElasticVoidRatio::Current),
        (StiffnessBasis::Strain, ElasticVoidRatio::Current),
    ] {
        let m = model_with_reading(basis, reading);
        let mut d = Driver::new(&m, 10.0 * KPA, 0.0);
        d.normal_to(50.0 * KPA, 40).expect("load");
        let v50 = d.st.v_mat;
        d.normal_to(350.0 * KPA, 60).expect("load");
        let v350 = d.st.v_mat;
        d.normal_to(400.0 * KPA, 10).expect("load");
        let v400 = d.st.v_mat;
        let ep400 = d.st.plastic_strain;
        // Nonlinear σ_n–v: the virgin secant stiffness over 350–400 kPa ≫ that over 10–50 kPa.
        let k_low = 40.0 * KPA / v50;
        let k_high = 50.0 * KPA / (v400 - v350);
        assert!(
            k_high > 3.0 * k_low,
            "{basis:?}: stiffening with σ_n ({k_high:.3e} vs {k_low:.3e})"
        );
        // Virgin loading: purely normal plastic closure (c0 limit), no shear.
        assert!(ep400[2] > 0.0, "{basis:?}: plastic closure");
        assert_eq!((ep400[0], ep400[1]), (0.0, 0.0));
        assert_eq!(d.tau(), 0.0);
        // Unloading 400 → 100 kPa: elastic, ε^p unchanged.
        d.normal_to(100.0 * KPA, 60).expect("unload");
        assert_eq!(d.st.plastic_strain, ep400, "{basis:?}: unloading must be elastic");
        assert_eq!(d.st.branch, GpBranch::Elastic);
        let v100 = d.st.v_mat;
        assert!(v100 < v400 && v100 > 0.0, "residual closure after unloading");
        // Reloading 100 → 800 kPa: plastic again (σ_c,max memory not used in H, gap G2.4).
        d.normal_to(800.0 * KPA, 120).expect("reload");
        assert!(d.st.plastic_strain[2] > ep400[2]);
        assert!(d.st.sigma_c_max >= 800.0 * KPA * (1.0 - 1e-9));
        // Opening from 100 kPa (measured: 75.7 mm under `displacement` and 7.6 mm literally with
        // (1+e0)/e0; 190 mm and 8.8 mm with the current e, which grows as the layer opens).
        let fresh = m.init_state(100.0 * KPA).expect("init");
        let opens = |mm: f64| {
            m.update(&fresh, &Local3::new(0.0, 0.0, mm * MM))
                .expect("open")
                .state
                .open
        };
        let open_at = opening_from_100_kpa(&m) / MM;
        match (basis, reading) {
            (StiffnessBasis::Strain, ElasticVoidRatio::Initial) => assert!(opens(8.0) && !opens(7.0)),
            (StiffnessBasis::Strain, ElasticVoidRatio::Current) => assert!(opens(10.0) && !opens(8.0)),
            (StiffnessBasis::Displacement, ElasticVoidRatio::Initial) => {
                assert!(opens(80.0) && !opens(70.0))
            }
            (StiffnessBasis::Displacement, ElasticVoidRatio::Current) => {
                assert!(opens(200.0) && !opens(150.0))
            }
        }
        println!(
            "IF-1 {basis:?} {reading:?}: v(50 kPa) = {:.3} mm, v(400) = {:.3} mm, v(back at 100) = {:.3} mm, v(800) = {:.3} mm, e = {:.4}; opens from 100 kPa at {:.1} mm",
            v50 / MM,
            v400 / MM,
            v100 / MM,
            d.st.v_mat / MM,
            d.st.void_ratio,
            open_at
        );
    }
}

/// IF-1 path 10 → 400 → 100 → 800 kPa at τ = 0 through the Newton driver (every state checked
/// against e_min): closure at 400 kPa, at 800 kPa and the void ratio at the end.
fn if1_closures(m: &GpInterface) -> (f64, f64, f64) {
    let mut d = Driver::new(m, 10.0 * KPA, 0.0);
    d.normal_to(400.0 * KPA, 100).expect("load");
    let v400 = d.st.v_mat;
    d.normal_to(100.0 * KPA, 60).expect("unload");
    d.normal_to(800.0 * KPA, 120).expect("reload");
    (v400, d.st.v_mat, d.st.void_ratio)
}

/// Jump opening (m) from a fresh state at 100 kPa at which the interface opens (bisection).
fn opening_from_100_kpa(m: &GpInterface) -> f64 {
    let fresh = m.init_state(100.0 * KPA).expect("init");
    let opens = |dn: f64| {
        m.update(&fresh, &Local3::new(0.0, 0.0, dn))
            .expect("open")
            .state
            .open
    };
    let (mut closed_at, mut open_at) = (0.0, 0.4);
    for _ in 0..40 {
        let mid = 0.5 * (closed_at + open_at);
        if opens(mid) {
            open_at = mid;
        } else {
            closed_at = mid;
        }
    }
    open_at
}

#[test]
fn if1_closure_at_400_and_800_kpa_is_bounded_with_the_strain_reading() {
    // Issue 19, acceptance 1. Measured (mm at 400 / 800 kPa, e at the end): default 5.292 /
    // 6.061, e = 0.1742; the same normal reading without the bound 6.667 / 8.668, e = 0.1417
    // (below e_min); the legacy `displacement` reading 59.2 / 71.6, e = −0.645.
    let m = strain_model();
    assert_eq!(
        (m.params.normal_basis, m.params.void_ratio_bound),
        (StiffnessBasis::Strain, VoidRatioBound::Smooth)
    );
    let (v400, v800, e800) = if1_closures(&m);
    let unbounded = GpInterface::new(GpInterfaceParams {
        void_ratio_bound: VoidRatioBound::None,
        ..strain_params()
    })
    .expect("valid");
    let (u400, u800, ue800) = if1_closures(&unbounded);
    let (l400, l800, le800) = if1_closures(&model(StiffnessBasis::Displacement));
    let open = opening_from_100_kpa(&m);
    println!(
        "IF-1 closure (mm) at 400 / 800 kPa, e at the end: default {:.3} / {:.3}, e = {e800:.4}; \
         no bound {:.3} / {:.3}, e = {ue800:.4}; legacy displacement {:.1} / {:.1}, e = {le800:.3}; \
         default opens from 100 kPa after {:.3} mm; bound {:.3} mm",
        v400 / MM,
        v800 / MM,
        u400 / MM,
        u800 / MM,
        l400 / MM,
        l800 / MM,
        open / MM,
        closure_bound(&m) / MM
    );
    assert!(v400 > 5.0 * MM && v400 < 5.6 * MM, "v(400 kPa) = {v400}");
    assert!(v800 > 5.8 * MM && v800 < 6.4 * MM, "v(800 kPa) = {v800}");
    assert!(v800 < closure_bound(&m) && e800 > m.params.e_min);
    assert!(u400 > v400 && u800 > closure_bound(&unbounded) && ue800 < m.params.e_min);
    assert!(
        l400 > 50.0 * MM && le800 < 0.0,
        "the legacy reading closes beyond the layer"
    );
    assert!(
        open > 2.0 * MM && open < 10.0 * MM,
        "opening from 100 kPa after {open}"
    );
}

#[test]
fn strain_controlled_closure_toward_the_bound_needs_a_diverging_stress() {
    // A closure imposed in strain control (the element's view) from 100 kPa: σ_n grows like a
    // power of 1/x as the closure approaches (e0 − e_min)/(1 + e0)·t = 8 mm, and stays finite
    // with a finite tangent. Measured σ_n = 1.07 / 7.60 / 51.6 / 360 / 37 094 MPa at 4 / 6 / 7
    // / 7.5 / 7.9 mm.
    let m = strain_model();
    let bound = closure_bound(&m);
    let mut st = m.init_state(100.0 * KPA).expect("init");
    let mut rows = Vec::new();
    let steps = 790;
    for i in 1..=steps {
        let up = m
            .update(&st, &Local3::new(0.0, 0.0, -0.01 * MM))
            .expect("closure");
        assert!(up.tangent.iter().all(|v| v.is_finite()));
        st = up.state;
        if [400, 600, 700, 750, 790].contains(&i) {
            rows.push((st.v_mat / MM, st.stress[2] / KPA, st.void_ratio));
        }
    }
    println!(
        "strain-controlled closure (v mm, σn kPa, e): {rows:.4?}; bound {:.3} mm",
        bound / MM
    );
    for w in rows.windows(2) {
        assert!(w[1].1 > w[0].1, "σ_n grows with the closure: {rows:?}");
    }
    let (_, s_end, e_end) = rows[rows.len() - 1];
    assert!(
        s_end > 10.0 * 1e3 && s_end.is_finite(),
        "σ_n near the bound: {s_end} kPa"
    );
    assert!(e_end > m.params.e_min);
    // A closure past the bound is an error of the update (the caller cuts the step).
    let err = m
        .update(&st, &Local3::new(0.0, 0.0, -0.2 * MM))
        .expect_err("beyond the bound");
    assert!(err.to_string().contains("void-ratio bound"), "{err}");
}

// ---------------------------------------------------------------------------------------------
// IF-2 CNL monotonic shear and the G2.3 stiffness level

#[test]
fn if2_cnl_monotonic_state_dependence() {
    for basis in [StiffnessBasis::Displacement, StiffnessBasis::Strain] {
        let m = model(basis);
        let mut peaks = Vec::new();
        let mut v_end = Vec::new();
        let mut dv_end = Vec::new();
        for sn in [100.0, 200.0, 400.0, 800.0] {
            let rec = cnl_monotonic(&m, sn * KPA, 60.0 * MM, 0.25 * MM);
            let (u_p, tau_p) = peak(&rec);
            peaks.push(tau_p / (sn * KPA));
            let last = rec[rec.len() - 1];
            let before = rec[rec.len() - 41];
            v_end.push(last.2);
            dv_end.push((last.2 - before.2) / (last.0 - before.0));
            println!(
                "IF-2 {basis:?} σn = {sn} kPa: η_peak = {:.4} at u = {:.1} mm, τ(60 mm)/τ_peak = {:.4}, v(60 mm) = {:.3} mm, dv/du(50–60 mm) = {:.4}",
                tau_p / (sn * KPA),
                u_p / MM,
                last.1 / tau_p,
                last.2 / MM,
                dv_end[dv_end.len() - 1]
            );
        }
        for w in peaks.windows(2) {
            assert!(w[1] < w[0], "{basis:?}: peak ratio decreases with σ_n: {peaks:?}");
        }
        assert!(
            peaks[0] > m.params.mc,
            "{basis:?}: dense at 100 kPa: η_peak > M_c ({peaks:?})"
        );
        assert!(
            peaks[3] < m.params.mc,
            "{basis:?}: loose at 800 kPa: η_peak < M_c ({peaks:?})"
        );
        // Dilation at low σ_n and contraction at high σ_n (rate at large slip; both readings).
        assert!(dv_end[0] < 0.0, "{basis:?}: dilating at 100 kPa: {dv_end:?}");
        assert!(dv_end[3] > 0.0, "{basis:?}: contracting at 800 kPa: {dv_end:?}");
        for w in v_end.windows(2) {
            assert!(w[1] > w[0], "{basis:?}: net closure grows with σ_n: {v_end:?}");
        }
        if basis == StiffnessBasis::Strain {
            // Literal reading: net dilation at 100 kPa (spec IF-2 reference ≈ −1 mm).
            assert!(v_end[0] < 0.0, "literal: net dilation at 100 kPa: {v_end:?}");
            assert!(v_end[3] > 0.0, "literal: net contraction at 800 kPa: {v_end:?}");
        }
    }
}

#[test]
fn if2_literal_reading_is_much_stiffer_than_tables_3_and_4() {
    // Table 3 hyperbolic at σn = 100 kPa: τ(5 mm) ≈ 22.5 kPa; Table 4 EP reaches τ_f at ≈ 30 mm.
    let lit = cnl_monotonic(&model(StiffnessBasis::Strain), 100.0 * KPA, 30.0 * MM, 0.1 * MM);
    let disp = cnl_monotonic(
        &model(StiffnessBasis::Displacement),
        100.0 * KPA,
        60.0 * MM,
        0.1 * MM,
    );
    let t5_lit = tau_at(&lit, 5.0 * MM);
    let t5_disp = tau_at(&disp, 5.0 * MM);
    println!(
        "τ(5 mm): literal {:.1} kPa, displacement {:.1} kPa (hyperbolic 22.5)",
        t5_lit / KPA,
        t5_disp / KPA
    );
    assert!(t5_lit > 0.8 * peak(&lit).1, "literal: > 80 % of peak at 5 mm");
    assert!(
        t5_lit > 3.0 * 22.5 * KPA,
        "literal: > 3× the hyperbolic fit at 5 mm"
    );
    assert!(
        t5_disp > 0.5 * 22.5 * KPA && t5_disp < 2.0 * 22.5 * KPA,
        "displacement reading within 2× of Table 3"
    );
    let u95 = u_at_fraction(&disp, 0.95);
    assert!(
        u95 > 15.0 * MM && u95 < 60.0 * MM,
        "displacement reading: 95 % of peak at {u95}"
    );
}

#[test]
fn report_shear_displacement_at_50_and_95_percent_of_peak() {
    let start = Instant::now();
    let mut updates = 0_u64;
    let mut u95 = Vec::new();
    for basis in [StiffnessBasis::Displacement, StiffnessBasis::Strain] {
        let m = model(basis);
        // Far enough past the peak for each reading (peak at 110–130 mm and 15–17 mm).
        let (du, steps) = match basis {
            StiffnessBasis::Displacement => (0.25 * MM, 800),
            StiffnessBasis::Strain => (0.1 * MM, 600),
        };
        for sn in [100.0, 200.0, 400.0] {
            let mut d = Driver::new(&m, sn * KPA, 0.0);
            let mut rec = vec![(0.0, 0.0, 0.0)];
            for i in 1..=steps {
                d.step(du, 0.0).expect("CNL step");
                rec.push((i as f64 * du, d.st.stress[0], d.st.v_mat));
            }
            assert!(
                peak(&rec).0 < 0.8 * steps as f64 * du,
                "the peak lies inside the run"
            );
            updates += d.updates;
            let (u_p, t_p) = peak(&rec);
            let (a, b) = (u_at_fraction(&rec, 0.5), u_at_fraction(&rec, 0.95));
            u95.push(b);
            // Table 3 hyperbolic fit of the same tests, closed form (H4): u at τ = τ_f/2.
            let k_si = 600.0 * 9.81e3 * (sn / 101.3_f64).powf(0.85);
            let tau_f = sn * KPA * 41.5_f64.to_radians().tan();
            let u50_hyp = 0.5 * tau_f / (k_si * (1.0 - 0.9 * 0.5));
            println!(
                "{basis:?} σn = {sn} kPa: τ_peak = {:.1} kPa at {:.1} mm; u50 = {:.2} mm (hyperbolic {:.2}); u95 = {:.2} mm; τ(5 mm) = {:.1} kPa",
                t_p / KPA,
                u_p / MM,
                a / MM,
                u50_hyp / MM,
                b / MM,
                tau_at(&rec, 5.0 * MM) / KPA
            );
            assert!(a < b && a > 0.0);
            match basis {
                StiffnessBasis::Displacement => {
                    assert!(
                        (a / u50_hyp - 1.0).abs() < 0.25,
                        "displacement reading: u50 ≈ hyperbolic u50"
                    )
                }
                StiffnessBasis::Strain => assert!(a < 0.2 * u50_hyp, "literal reading: ≥ 5× stiffer"),
            }
        }
    }
    let secs = start.elapsed().as_secs_f64();
    println!(
        "monotonic CNL: {updates} updates in {secs:.3} s = {:.0} updates/s",
        updates as f64 / secs
    );
    for i in 0..3 {
        assert!(
            u95[i] > 4.0 * u95[i + 3],
            "displacement reading ≫ literal: {u95:?}"
        );
    }
    // Cyclic timing: 200 cycles of ±2 mm at 200 kPa through the Newton driver.
    let m = strain_model();
    let mut d = Driver::new(&m, 200.0 * KPA, 0.0);
    let start = Instant::now();
    for _ in 0..200 {
        for dx in [
            0.5, 0.5, 0.5, 0.5, -0.5, -0.5, -0.5, -0.5, -0.5, -0.5, -0.5, -0.5, 0.5, 0.5, 0.5, 0.5,
        ] {
            d.step(dx * MM, 0.0).expect("cyclic");
        }
    }
    let secs = start.elapsed().as_secs_f64();
    println!(
        "cyclic CNL (±2 mm): {} updates in {secs:.3} s = {:.0} updates/s, v = {:.2} mm",
        d.updates,
        d.updates as f64 / secs,
        d.st.v_mat / MM
    );
}

/// CNL monotonic shear to 200 mm in 0.25 mm steps: (τ_peak, u50, u95, v at 200 mm).
fn crosscheck_row(m: &GpInterface, sigma_n: f64) -> (f64, f64, f64, f64) {
    let rec = cnl_monotonic(m, sigma_n, 200.0 * MM, 0.25 * MM);
    let v_end = rec[rec.len() - 1].2;
    (
        peak(&rec).1,
        u_at_fraction(&rec, 0.5),
        u_at_fraction(&rec, 0.95),
        v_end,
    )
}

#[test]
fn default_keeps_the_shear_curves_of_the_crosscheck() {
    // Issue 19, acceptance 1: the directional basis of H (I16) leaves the shear curves of the
    // cross-check (inputs/point/interface_crosscheck.yaml) where the legacy `displacement`
    // reading had them. Measured (100 / 200 / 400 kPa): u50 14.47 / 14.38 / 14.27 mm against
    // 14.54 / 14.47 / 14.38 mm, u95 53.47 / 54.40 / 55.17 mm against 53.78 / 54.65 / 55.38 mm,
    // peaks equal to 0.1 kPa; the normal displacement at 200 mm is −2.24 / −0.84 / +0.57 mm
    // (dilation, dilation, contraction; legacy −2.23 / −0.83 / +0.59 mm). Those are the strain
    // reading's, whose dilatancy is also held to 0.05 mm of the legacy one; the default's shear
    // curves are held to the same tolerances (its v(200 mm), printed, is in the module docs).
    let old = model(StiffnessBasis::Displacement);
    let readings = [
        (
            "default",
            GpInterface::new(GpInterfaceParams::default()).expect("the default"),
        ),
        ("strain reading", strain_model()),
    ];
    for ((name, new), sn) in readings
        .iter()
        .flat_map(|r| [100.0, 200.0, 400.0].map(|sn| (r, sn)))
    {
        let (tp, u50, u95, v) = crosscheck_row(new, sn * KPA);
        let (tp0, u50_0, u95_0, v0) = crosscheck_row(&old, sn * KPA);
        println!(
            "cross-check σn = {sn} kPa: {name} τp = {:.2} kPa, u50 = {:.2} mm, u95 = {:.2} mm, \
             v(200 mm) = {:.3} mm; legacy {:.2} kPa, {:.2} mm, {:.2} mm, {:.3} mm",
            tp / KPA,
            u50 / MM,
            u95 / MM,
            v / MM,
            tp0 / KPA,
            u50_0 / MM,
            u95_0 / MM,
            v0 / MM
        );
        assert!((tp / tp0 - 1.0).abs() < 0.002, "peak {tp} vs {tp0}");
        assert!((u50 / u50_0 - 1.0).abs() < 0.01, "u50 {u50} vs {u50_0}");
        assert!((u95 / u95_0 - 1.0).abs() < 0.01, "u95 {u95} vs {u95_0}");
        if *name == "strain reading" {
            assert!((v - v0).abs() < 0.05 * MM, "v(200 mm) {v} vs {v0}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// IF-3 CNL cyclic shear

fn cyclic_cnl(
    m: &GpInterface,
    sn: f64,
    amp: f64,
    cycles: usize,
    steps_quarter: usize,
) -> (Vec<f64>, GpInterfaceState) {
    let mut d = Driver::new(m, sn, 0.0);
    let du = amp / steps_quarter as f64;
    let mut v_cycle = Vec::new();
    for _ in 0..cycles {
        for (sign, n) in [
            (1.0, steps_quarter),
            (-1.0, 2 * steps_quarter),
            (1.0, steps_quarter),
        ] {
            for _ in 0..n {
                d.step(sign * du, 0.0).expect("cyclic step");
            }
        }
        v_cycle.push(d.st.v_mat);
    }
    (v_cycle, d.st)
}

#[test]
fn if3_cnl_cyclic_contraction_accumulates() {
    let with = |f: fn(&mut GpInterfaceParams)| {
        let mut p = strain_params();
        f(&mut p);
        GpInterface::new(p).expect("valid")
    };
    let m = strain_model();
    let no_breakage = with(|p| p.a = 1e12);
    let memory = with(|p| p.fh_mode = FhMode::Memory);
    let literal = model(StiffnessBasis::Strain);
    for sn in [200.0, 400.0] {
        let (v, st) = cyclic_cnl(&m, sn * KPA, 5.0 * MM, 10, 10);
        let (v_nb, st_nb) = cyclic_cnl(&no_breakage, sn * KPA, 5.0 * MM, 10, 10);
        let (v_mem, _) = cyclic_cnl(&memory, sn * KPA, 5.0 * MM, 10, 10);
        let (v_lit, _) = cyclic_cnl(&literal, sn * KPA, 5.0 * MM, 10, 10);
        let incs = |v: &[f64]| -> Vec<f64> {
            v.windows(2)
                .map(|w| ((w[1] - w[0]) / MM * 1e4).round() / 1e4)
                .collect()
        };
        println!(
            "IF-3 σn = {sn} kPa: v1 = {:.3} mm, v10 = {:.3} mm, per-cycle {:?}; Δe_c = {:.2e}; no breakage v10 = {:.3} mm; \
             fh memory v10 = {:.3} mm per-cycle {:?}; literal v10 = {:.3} mm per-cycle {:?}",
            v[0] / MM,
            v[9] / MM,
            incs(&v),
            st.delta_e_c,
            v_nb[9] / MM,
            v_mem[9] / MM,
            incs(&v_mem),
            v_lit[9] / MM,
            incs(&v_lit)
        );
        for w in v.windows(2) {
            assert!(w[1] > w[0], "contraction accumulates every cycle: {v:?}");
        }
        assert!(st.delta_e_c > 0.0 && st_nb.delta_e_c < 1e-9);
        assert!(v[9] > v_nb[9], "breakage increases the accumulated contraction");
        assert!(
            v_mem[9] < v[9],
            "the memory reading of f_h reduces cyclic contraction"
        );
    }
}

/// Per-cycle increments of the closure v (mm) from the end-of-cycle values (cycles 2 … 10).
fn per_cycle_mm(v: &[f64]) -> Vec<f64> {
    v.windows(2).map(|w| (w[1] - w[0]) / MM).collect()
}

fn rounded(v: &[f64]) -> Vec<f64> {
    v.iter().map(|x| (x * 1e3).round() / 1e3).collect()
}

#[test]
fn if3_cyclic_contraction_decays_with_the_default_elastic_reading() {
    // Spec IF-3: "contraction accumulating with cycles at a decreasing rate". Criterion: every
    // per-cycle increment of the closure is positive (contraction accumulates) and smaller
    // than the one before (the accumulated closure is concave in the cycle number), from
    // cycle 2 to cycle 10; and the cycle-10 increment is below 0.9× the cycle-2 increment, so
    // the decay is not a round-off trend (measured 0.87 at both stresses).
    let m = model(StiffnessBasis::Displacement);
    assert_eq!(m.params.elastic_void_ratio, ElasticVoidRatio::Initial);
    for sn in [200.0, 400.0] {
        let (v, st) = cyclic_cnl(&m, sn * KPA, 5.0 * MM, 10, 10);
        let inc = per_cycle_mm(&v);
        println!(
            "IF-3 decay, e0 in (1+e)/e, σn = {sn} kPa: v1 = {:.3} mm, v10 = {:.3} mm, per-cycle {:?} mm, c10/c2 = {:.3}, e10 = {:.4}",
            v[0] / MM,
            v[9] / MM,
            rounded(&inc),
            inc[8] / inc[0],
            st.void_ratio
        );
        assert_decaying_contraction(&inc, 0.9);
    }
}

/// Per-cycle closures `inc` (cycles 2 to 10) that are all positive (contraction accumulates),
/// each smaller than the one before, and the last below `ratio` times the first.
fn assert_decaying_contraction(inc: &[f64], ratio: f64) {
    assert!(inc.iter().all(|&x| x > 0.0), "contraction accumulates: {inc:?}");
    for w in inc.windows(2) {
        assert!(w[1] < w[0], "decreasing rate: {inc:?}");
    }
    assert!(inc[8] < ratio * inc[0], "cycle 10 vs cycle 2: {inc:?}");
}

#[test]
fn if3_cyclic_contraction_decays_within_the_bound_with_the_strain_reading() {
    // Issue 19: with the void-ratio bound the per-cycle closure of IF-3 (±5 mm, 10 cycles)
    // falls every cycle and much faster than with the legacy reading (c10/c2 = 0.87). Measured
    // per-cycle 0.810 → 0.258 mm at 200 kPa (c10/c2 = 0.32, v10 = 5.37 mm) and 0.870 → 0.249
    // mm at 400 kPa (0.29, 5.56 mm).
    let m = strain_model();
    for sn in [200.0, 400.0] {
        let (v, st) = cyclic_cnl(&m, sn * KPA, 5.0 * MM, 10, 10);
        let inc = per_cycle_mm(&v);
        println!(
            "IF-3 default, σn = {sn} kPa: v10 = {:.3} mm, per-cycle {:?} mm, c10/c2 = {:.3}, e10 = {:.4}",
            v[9] / MM,
            rounded(&inc),
            inc[8] / inc[0],
            st.void_ratio
        );
        assert_decaying_contraction(&inc, 0.4);
        assert!(v[9] < closure_bound(&m));
    }
}

#[test]
fn if3_current_void_ratio_reading_contracts_at_a_growing_rate() {
    // The other reading, as documented: with the current e in (1+e)/e the elastic part
    // stiffens as the layer densifies, more of the imposed ±5 mm becomes plastic slip, and
    // the per-cycle contraction grows (measured c10/c2 = 1.23 at 200 kPa, 1.28 at 400 kPa).
    let p: GpInterfaceParams = serde_json::from_str(
        r#"{"elastic_void_ratio": "current", "normal_basis": "displacement",
            "void_ratio_bound": "none", "reversal_branch": "start"}"#,
    )
    .expect("named options");
    assert_eq!(p.elastic_void_ratio, ElasticVoidRatio::Current);
    assert!(serde_json::from_str::<GpInterfaceParams>(r#"{"elastic_void_ratio": "e0"}"#).is_err());
    let m = GpInterface::new(p).expect("valid");
    for sn in [200.0, 400.0] {
        let (v, _) = cyclic_cnl(&m, sn * KPA, 5.0 * MM, 10, 10);
        let inc = per_cycle_mm(&v);
        println!(
            "IF-3 current e in (1+e)/e, σn = {sn} kPa: v10 = {:.3} mm, per-cycle {:?} mm, c10/c2 = {:.3}",
            v[9] / MM,
            rounded(&inc),
            inc[8] / inc[0]
        );
        for w in inc.windows(2) {
            assert!(w[1] > w[0], "growing rate: {inc:?}");
        }
        assert!(inc[8] > 1.1 * inc[0], "cycle 10 vs cycle 2: {inc:?}");
    }
}

#[test]
fn g7_which_ingredient_produces_cyclic_decay() {
    // Spec G7: f_h option, breakage, elastic void ratio, stiffness reading. IF-3 at ±5 mm,
    // σn = 200 kPa, 10 cycles; per-cycle closure increments (cycles 2 … 10) and c10/c2.
    // Under the displacement reading the sign of the trend follows the elastic void ratio
    // alone: e0 decays, the current e grows, whatever f_h and breakage do.
    type Case = (&'static str, fn(&mut GpInterfaceParams));
    let cases: [Case; 8] = [
        ("e0, f_h literal (default)", |_| {}),
        ("current e, f_h literal", |p| {
            p.elastic_void_ratio = ElasticVoidRatio::Current
        }),
        ("e0, f_h memory", |p| p.fh_mode = FhMode::Memory),
        ("current e, f_h memory", |p| {
            p.elastic_void_ratio = ElasticVoidRatio::Current;
            p.fh_mode = FhMode::Memory;
        }),
        ("e0, no breakage", |p| p.a = 1e12),
        ("current e, no breakage", |p| {
            p.elastic_void_ratio = ElasticVoidRatio::Current;
            p.a = 1e12;
        }),
        ("e0, strain (literal) reading", |p| {
            p.stiffness_basis = StiffnessBasis::Strain
        }),
        ("current e, strain (literal) reading", |p| {
            p.elastic_void_ratio = ElasticVoidRatio::Current;
            p.stiffness_basis = StiffnessBasis::Strain;
        }),
    ];
    for (name, set) in cases {
        let mut p = legacy_params(StiffnessBasis::Displacement);
        set(&mut p);
        p.normal_basis = p.stiffness_basis;
        let (basis, reading) = (p.stiffness_basis, p.elastic_void_ratio);
        let m = GpInterface::new(p).expect("valid");
        let (v, _) = cyclic_cnl(&m, 200.0 * KPA, 5.0 * MM, 10, 10);
        let inc = per_cycle_mm(&v);
        let ratio = inc[8] / inc[0];
        println!(
            "G7 {name}: v10 = {:.3} mm, per-cycle {:?} mm, c10/c2 = {ratio:.3}",
            v[9] / MM,
            rounded(&inc)
        );
        match (basis, reading) {
            (StiffnessBasis::Displacement, ElasticVoidRatio::Initial) => {
                assert!(ratio < 0.95, "{name}: decays ({ratio})")
            }
            (StiffnessBasis::Displacement, ElasticVoidRatio::Current) => {
                assert!(ratio > 1.05, "{name}: grows ({ratio})")
            }
            // The literal reading decays with either elastic void ratio (±5 mm is mostly
            // plastic slip there, so the elastic stiffening hardly matters).
            (StiffnessBasis::Strain, _) => assert!(ratio < 0.9, "{name}: decays ({ratio})"),
        }
    }
}

#[test]
fn if3_cyclic_breakage_is_c_times_faster_per_unit_work() {
    // (I21): χ = c on cyclic branches. Compare dΔe_c/dW_p over a virgin and a cyclic stage.
    let m = strain_model();
    let mut d = Driver::new(&m, 200.0 * KPA, 0.0);
    for _ in 0..20 {
        d.step(0.1 * MM, 0.0).expect("virgin");
    }
    let (w0, e0) = (d.st.plastic_work, d.st.delta_e_c);
    d.step(0.1 * MM, 0.0).expect("virgin");
    let virgin = (d.st.delta_e_c - e0) / (d.st.plastic_work - w0);
    d.step(-0.5 * MM, 0.0).expect("reversal");
    for _ in 0..3 {
        d.step(-0.1 * MM, 0.0).expect("cyclic");
    }
    let (w1, e1) = (d.st.plastic_work, d.st.delta_e_c);
    d.step(-0.1 * MM, 0.0).expect("cyclic");
    assert_eq!(d.st.branch, GpBranch::Cyclic);
    let cyclic = (d.st.delta_e_c - e1) / (d.st.plastic_work - w1);
    let p = &m.params;
    // Ratio corrected for the (a + bW_p)² denominator at the two work levels.
    let ratio = cyclic / virgin * ((p.a + p.b * w1) / (p.a + p.b * w0)).powi(2);
    assert!(
        (ratio - p.c).abs() < 0.05 * p.c,
        "cyclic/virgin breakage rate ratio {ratio}"
    );
}

// ---------------------------------------------------------------------------------------------
// IF-4 CNS

#[test]
fn if4_cns_monotonic_and_cyclic() {
    let m = strain_model();
    for k_kpa_mm in [500.0, 2000.0] {
        let k = k_kpa_mm * KPA / MM;
        let mut d = Driver::new(&m, 200.0 * KPA, k);
        let mut min_sn = f64::INFINITY;
        let mut rows = Vec::new();
        for i in 0..600 {
            d.step(0.1 * MM, 0.0).expect("CNS step");
            if i % 50 == 49 {
                println!(
                    "  CNS K={k_kpa_mm}: u = {:.1} mm σn = {:.1} kPa τ = {:.1} kPa v = {:.3} mm",
                    (i + 1) as f64 * 0.1,
                    d.st.stress[2] / KPA,
                    d.st.stress[0] / KPA,
                    d.st.v_mat / MM
                );
            }
            min_sn = min_sn.min(d.st.stress[2]);
            // Boundary condition: σ_n − σ_n0 = K·δ_n (dilation, δ_n > 0, raises σ_n).
            let expect = 200.0 * KPA + k * d.st.jump[2];
            assert!((d.st.stress[2] - expect).abs() < 1e-6 * expect);
            rows.push((d.st.stress[2], d.st.v_mat));
        }
        let (sn_end, v_end) = rows[rows.len() - 1];
        let (sn_mid, v_mid) = rows[rows.len() / 2];
        println!(
            "IF-4 K = {k_kpa_mm} kPa/mm: min σn = {:.1} kPa, σn(20 mm) = {:.1} kPa, v = {:.3} mm",
            min_sn / KPA,
            sn_end / KPA,
            v_end / MM
        );
        // Dense state: once dilating (v decreasing) σ_n rises.
        assert!(v_end < v_mid, "dilation in the second half");
        assert!(sn_end > sn_mid, "σ_n increases while dilating");
        // Cyclic CNS: contraction accumulates, σ_n and the cycle peak τ degrade.
        let mut c = Driver::new(&m, 200.0 * KPA, k);
        let mut peaks = Vec::new();
        let mut sn_cycle = Vec::new();
        for _ in 0..8 {
            let mut tmax: f64 = 0.0;
            for (sign, n) in [(1.0, 10), (-1.0, 20), (1.0, 10)] {
                for _ in 0..n {
                    c.step(sign * 0.2 * MM, 0.0).expect("cyclic CNS");
                    tmax = tmax.max(c.st.stress[0]);
                }
            }
            peaks.push(tmax);
            sn_cycle.push(c.st.stress[2]);
        }
        assert!(
            sn_cycle[7] < sn_cycle[1],
            "σ_n degrades with cycles: {sn_cycle:?}"
        );
        assert!(peaks[7] < peaks[1], "cycle peak τ degrades: {peaks:?}");
    }
}

// ---------------------------------------------------------------------------------------------
// IF-5 3D coupling

#[test]
fn if5a_orthogonal_shear_after_s_shear() {
    let m = strain_model();
    let mut d = Driver::new(&m, 200.0 * KPA, 0.0);
    for _ in 0..50 {
        d.step(0.1 * MM, 0.0).expect("s shear");
    }
    let ts0 = d.st.stress[0];
    let mut prev_s = ts0;
    for _ in 0..200 {
        d.step(0.0, 0.1 * MM).expect("a shear");
        assert!(d.st.stress[0] <= prev_s * (1.0 + 1e-12), "τ_s never rises");
        prev_s = d.st.stress[0];
    }
    assert!(
        d.st.stress[0] < 0.5 * ts0,
        "τ_s drops: {} → {}",
        ts0,
        d.st.stress[0]
    );
    assert!(
        d.st.stress[1] > 2.0 * d.st.stress[0],
        "τ_a builds up: {}",
        d.st.stress[1]
    );
    assert!(d.tau() / d.st.stress[2] < 1.2 * m.peak_ratio(-0.3));
}

/// Radial shear to 10 mm, then three revolutions of a 10 mm circle (200 steps per half turn) at
/// CNL σ_n; asserts a bounded stress ratio inside the max-history circle at every step and
/// returns the range of the lead of τ over the displacement angle (after the first quarter
/// turn) and the final |τ|/σ_n.
fn circular_path(m: &GpInterface, sigma_n: f64) -> ((f64, f64), f64) {
    let mut d = Driver::new(m, sigma_n, 0.0);
    let radius = 10.0 * MM;
    for _ in 0..50 {
        d.step(radius / 50.0, 0.0).expect("radial");
    }
    let n = 200;
    let mut prev = (radius, 0.0);
    let mut lead_range = (f64::INFINITY, f64::NEG_INFINITY);
    for i in 1..=3 * 2 * n {
        let th = std::f64::consts::PI * i as f64 / n as f64;
        let now = (radius * th.cos(), radius * th.sin());
        d.step(now.0 - prev.0, now.1 - prev.1).expect("circle");
        prev = now;
        let eta = d.tau() / d.st.stress[2];
        assert!(eta.is_finite() && eta < 1.2, "bounded stress ratio {eta}");
        assert!(
            d.st.eta_max >= eta * (1.0 - 1e-12),
            "state inside the max circle (G7)"
        );
        if i > n / 2 {
            // τ lies between the radial direction (elastic) and the slip direction (θ + 90°).
            let lead = (d.st.stress[1].atan2(d.st.stress[0]) - th + std::f64::consts::PI)
                .rem_euclid(2.0 * std::f64::consts::PI)
                - std::f64::consts::PI;
            lead_range = (lead_range.0.min(lead), lead_range.1.max(lead));
        }
    }
    (lead_range, d.tau() / d.st.stress[2])
}

#[test]
fn if5b_circular_path_is_bounded_and_follows_the_motion() {
    // Boundedness and the max-history circle hold for both elastic readings (asserted inside).
    // Whether τ keeps up with the motion depends on where the reversal rule (I18) places its
    // reversal points along the turning path, and that is chaotic in the parameters (spec G7):
    // with the current void ratio the lead stays in [−0.17, 0.65] rad at the seed D_s0 but
    // reaches −0.78 rad with D_s0 × 0.9 and the stress collapses to |τ|/σn = 0.06 with
    // D_s0 × 0.95; with e0 (default) it ends at |τ|/σn = 0.13 lagging 0.96 rad at the seed
    // D_s0 but stays in [−0.15, 0.85] rad with D_s0 × 1.1 (module docs, "Findings"). The lead
    // bound is therefore checked for the reading it was written for; the sweep is printed.
    let current = model_with_reading(StiffnessBasis::Displacement, ElasticVoidRatio::Current);
    let (lead_range, eta_end) = circular_path(&current, 200.0 * KPA);
    println!(
        "IF-5b current e: lead of τ over the displacement angle in [{:.4}, {:.4}] rad, final |τ|/σn = {:.3}",
        lead_range.0, lead_range.1, eta_end
    );
    assert!(
        lead_range.0 > -std::f64::consts::FRAC_PI_4 && lead_range.1 < std::f64::consts::FRAC_PI_2,
        "τ rotates with the motion: {lead_range:?}"
    );
    for reading in [ElasticVoidRatio::Initial, ElasticVoidRatio::Current] {
        for factor in [0.9, 0.95, 1.0, 1.05, 1.1] {
            let m = GpInterface::new(GpInterfaceParams {
                ds0: factor * strain_params().ds0,
                elastic_void_ratio: reading,
                ..legacy_params(StiffnessBasis::Displacement)
            })
            .expect("valid");
            let (lead, eta) = circular_path(&m, 200.0 * KPA);
            println!(
                "IF-5b {reading:?} e, D_s0 × {factor}: lead in [{:.3}, {:.3}] rad, final |τ|/σn = {eta:.3}",
                lead.0, lead.1
            );
        }
    }
}

#[test]
fn if5c_reversal_in_s_with_axial_shear() {
    let m = strain_model();
    let mut d = Driver::new(&m, 200.0 * KPA, 0.0);
    for _ in 0..40 {
        d.step(0.1 * MM, 0.05 * MM).expect("diagonal");
    }
    let before = d.st.clone();
    assert!(before.stress[0] > 0.0 && before.stress[1] > 0.0);
    d.step(-0.05 * MM, 0.0).expect("reverse s");
    let dep_s = d.st.plastic_strain[0] - before.plastic_strain[0];
    assert!(
        dep_s < 0.0,
        "plastic shear strain opposite to the old τ_s: {dep_s}"
    );
    assert_eq!(d.st.branch, GpBranch::Cyclic);
    let r = m.stress_ratio(&before.stress);
    assert!((d.st.reversal_point[0] - r[0]).abs() < 1e-12 && (d.st.reversal_point[1] - r[1]).abs() < 1e-12);
    assert!(d.st.stress[0] < before.stress[0]);
    // Flow direction at the image point: its shear part points against the old τ_s.
    let f = m.functions(&d.st, &Vector3::new(-1e-4, 0.0, 0.0));
    assert!(f.ng[0] < 0.0 && f.n[0] < 0.0);
    assert!(f.map.ratio <= MAPPING_RATIO_CAP);
}

// ---------------------------------------------------------------------------------------------
// IF-6 opening, shear while open, re-closure

#[test]
fn if6_open_shear_reclose_keeps_memory() {
    let m = strain_model();
    let mut d = Driver::new(&m, 100.0 * KPA, 0.0);
    for _ in 0..30 {
        d.step(0.1 * MM, 0.0).expect("shear");
    }
    let st = d.st.clone();
    // Open: impose an opening jump well beyond the elastic recovery.
    let mut s = m
        .update(&st, &Local3::new(0.0, 0.0, 200.0 * MM))
        .expect("open")
        .state;
    assert!(s.open && s.gap > 0.0);
    assert_eq!(GpInterface::traction(&s), Local3::zeros());
    let frozen = (
        s.void_ratio,
        s.plastic_work,
        s.eta_max,
        s.delta_e_c,
        s.v_mat,
        s.sigma_c_max,
    );
    assert!((s.w_open - s.v_mat).abs() < 1e-15);
    let out = GpInterface::outputs(&s);
    assert!(out.open && (out.opening - s.gap).abs() < 1e-15 && (out.normal - s.v_mat).abs() < 1e-15);
    // Shear while open: free, stresses zero, material frozen.
    let up = m
        .update(&s, &Local3::new(3.0 * MM, -MM, 0.0))
        .expect("open shear");
    s = up.state;
    assert_eq!(GpInterface::traction(&s), Local3::zeros());
    assert_eq!(
        (
            s.void_ratio,
            s.plastic_work,
            s.eta_max,
            s.delta_e_c,
            s.v_mat,
            s.sigma_c_max
        ),
        frozen
    );
    assert!(up.tangent.iter().all(|v| v.is_finite()) && up.tangent[(2, 2)] > 0.0);
    let gap = s.gap;
    // Partial closure: still open, gap reduced.
    s = m
        .update(&s, &Local3::new(0.0, 0.0, -0.5 * gap))
        .expect("closing")
        .state;
    assert!(s.open && (s.gap - 0.5 * gap).abs() < 1e-12);
    // Re-close beyond contact: τ restarts from 0 (no shear in this step), v_mat continuous.
    let over = 0.01 * MM;
    let up = m
        .update(&s, &Local3::new(0.0, 0.0, -0.5 * gap - over))
        .expect("reclose");
    let c = up.state;
    assert!(!c.open && c.gap == 0.0);
    assert_eq!((c.stress[0], c.stress[1]), (0.0, 0.0));
    assert!(c.stress[2] > m.params.sigma_min);
    assert!(
        (c.v_mat - (frozen.4 + over)).abs() < 1e-9,
        "v_mat continues from w_open: {} vs {}",
        c.v_mat,
        frozen.4 + over
    );
    assert!(c.plastic_work >= frozen.1 && c.eta_max >= frozen.2);
    assert_eq!(c.reversal_point, [0.0, 0.0]);
    // Closure bookkeeping: the material lost contact at the closure where it regains it, so
    // after a full open/close cycle the total closure w = −δ_n equals v_mat again (g_frozen = 0).
    assert!(c.g_frozen.abs() < 1e-12, "g_frozen = {}", c.g_frozen);
    assert!((-c.jump[2] - c.v_mat).abs() < 1e-12);
}

// ---------------------------------------------------------------------------------------------
// IF-7 robustness and hard cases

#[test]
fn if7_result_is_independent_of_stol() {
    let mut taus = Vec::new();
    let mut reversed = Vec::new();
    for stol in [1e-3, 1e-4, 1e-5] {
        let mut p = strain_params();
        p.integration.stol = stol;
        let m = GpInterface::new(p).expect("valid");
        // One big strain-controlled step (δ_n fixed) so the substepping decides the accuracy.
        let st = m.init_state(200.0 * KPA).expect("init");
        let u = m
            .update(&st, &Local3::new(10.0 * MM, 2.0 * MM, 0.0))
            .expect("update");
        // Then a big reversal step (reversal rule, cyclic branch, mapping ratio cap).
        let r = m
            .update(&u.state, &Local3::new(-6.0 * MM, 1.0 * MM, 0.1 * MM))
            .expect("reversal");
        taus.push((u.state.stress, u.substeps));
        reversed.push(r.state.stress);
    }
    println!("STOL 1e-3/1e-4/1e-5 after the reversal: {reversed:?}");
    println!("STOL 1e-3/1e-4/1e-5: {taus:?}");
    let rel = |a: &[f64; 3], b: &[f64; 3]| {
        let d = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
        d / (b[0].powi(2) + b[1].powi(2) + b[2].powi(2)).sqrt()
    };
    assert!(rel(&taus[0].0, &taus[2].0) < 1e-2, "STOL 1e-3 vs 1e-5");
    assert!(rel(&taus[1].0, &taus[2].0) < 1e-3, "STOL 1e-4 vs 1e-5");
    assert!(taus[2].1 > taus[0].1, "more substeps for a tighter STOL");
    assert!(
        rel(&reversed[0], &reversed[2]) < 1e-2,
        "reversal: STOL 1e-3 vs 1e-5"
    );
    assert!(
        rel(&reversed[1], &reversed[2]) < 1e-3,
        "reversal: STOL 1e-4 vs 1e-5"
    );
}

#[test]
fn if7_hard_cases_zero_stress_tension_tiny_reversals_huge_increments() {
    let m = strain_model();
    // Zero and tensile initial normal stress.
    let z = m.init_state(0.0).expect("zero stress");
    assert_eq!(z.stress[2], m.params.sigma_min);
    assert!(m.init_state(-1.0).is_err() && m.init_state(f64::NAN).is_err());
    // Shear at σ_min: finite, no tension.
    let u = m
        .update(&z, &Local3::new(1.0 * MM, 0.0, 0.0))
        .expect("shear at σ_min");
    assert!(u.state.stress.iter().all(|v| v.is_finite()) && u.state.stress[2] >= 0.0);
    // A pure opening jump from zero stress opens at once.
    let o = m.update(&z, &Local3::new(0.0, 0.0, 50.0 * MM)).expect("open");
    assert!(o.state.open && GpInterface::traction(&o.state).norm() == 0.0);
    // η → 0 reversals: tiny alternating shear around τ = 0.
    let mut st = m.init_state(100.0 * KPA).expect("init");
    for i in 0..200 {
        let sgn = if i % 2 == 0 { 1.0 } else { -1.0 };
        let up = m
            .update(&st, &Local3::new(sgn * 1e-9, 0.0, 0.0))
            .expect("tiny reversal");
        assert!(up.tangent.iter().all(|v| v.is_finite()));
        st = up.state;
    }
    assert!(st.stress.iter().all(|v| v.is_finite()));
    // 100× the usual increment (20 mm in one step, δ_n fixed) equals 100 steps of 0.2 mm.
    let s0 = m.init_state(200.0 * KPA).expect("init");
    let big = m
        .update(&s0, &Local3::new(20.0 * MM, 0.0, 0.0))
        .expect("huge increment");
    let mut small = s0.clone();
    for _ in 0..100 {
        small = m
            .update(&small, &Local3::new(0.2 * MM, 0.0, 0.0))
            .expect("small")
            .state;
    }
    let d = (big.state.stress[0] - small.stress[0]).abs() / small.stress[0];
    assert!(
        d < 1e-2,
        "one 20 mm step vs 100 steps: {} vs {}",
        big.state.stress[0],
        small.stress[0]
    );
    assert!(big.substeps > 1);
    let e = m.update(&s0, &Local3::new(f64::NAN, 0.0, 0.0));
    assert!(e.is_err());
}

/// The record of [`ten_thousand_cycles`].
struct CycleRecord {
    /// Closure v_mat (m) at the end of each cycle (index 0 = cycle 1).
    v_end: Vec<f64>,
    /// Smallest void ratio of any update.
    e_lowest: f64,
    /// Final state.
    state: GpInterfaceState,
}

/// 10 000 shear cycles (±0.5 mm, with an axial component 0.2× as large) at σ_n ≈ 300 kPa. One
/// update per quarter cycle: δ_n is predicted from the last tangent so that σ_n returns to its
/// target (an explicit drift-corrected CNL, cheaper than the Newton driver). Every state is
/// checked finite, closed and, for a bounded model, at or above e_min.
fn ten_thousand_cycles(m: &GpInterface) -> CycleRecord {
    let target = 300.0 * KPA;
    let mut st = m.init_state(target).expect("init");
    let mut k = m.update(&st, &Local3::zeros()).expect("tangent").tangent;
    let start = Instant::now();
    let (mut updates, mut substeps) = (0_u64, 0_u64);
    let mut v_end = Vec::with_capacity(10_000);
    let mut e_lowest = st.void_ratio;
    let du = 0.5 * MM;
    for _ in 0..10_000 {
        for dx in [du, -du, -du, du] {
            let (ds, da) = (dx, 0.2 * dx);
            // ΔT_n = −(σ_target − σ_n) = K_ns·δs + K_na·δa + K_nn·δn.
            let dt_n = -(target - st.stress[2]);
            let dn = (dt_n - k[(2, 0)] * ds - k[(2, 1)] * da) / k[(2, 2)];
            let up = m.update(&st, &Local3::new(ds, da, dn)).expect("cycle");
            updates += 1;
            substeps += up.substeps as u64;
            k = up.tangent;
            st = up.state;
            assert!(st.stress.iter().all(|v| v.is_finite()) && !st.open);
            check_void_ratio(m, &st);
            e_lowest = e_lowest.min(st.void_ratio);
        }
        v_end.push(st.v_mat);
    }
    let secs = start.elapsed().as_secs_f64();
    let at = |c: usize| (c, v_end[c - 1] / MM);
    println!(
        "10 000 cycles: {updates} updates ({substeps} substeps) in {secs:.3} s = {:.0} updates/s; \
         σn = {:.1} kPa, e = {:.4} (lowest {e_lowest:.5}), W_p = {:.3e} Pa; (cycle, v in mm): {:.4?}",
        updates as f64 / secs,
        st.stress[2] / KPA,
        st.void_ratio,
        st.plastic_work,
        [at(1), at(10), at(100), at(1000), at(10_000)]
    );
    let finite = st
        .stress
        .iter()
        .chain(st.strain.iter())
        .chain(st.plastic_strain.iter())
        .all(|v| v.is_finite());
    assert!(finite && st.void_ratio.is_finite() && st.plastic_work.is_finite() && st.delta_e_c.is_finite());
    assert!(
        (st.stress[2] - target).abs() < 0.05 * target,
        "σ_n kept near its target: {}",
        st.stress[2]
    );
    CycleRecord {
        v_end,
        e_lowest,
        state: st,
    }
}

#[test]
fn if7_ten_thousand_cycles_without_nan() {
    // The legacy `displacement` reading has no bound: finite, but the layer closes by more than
    // its thickness (measured 109.0 mm, e = −1.11; module docs, "Findings").
    let rec = ten_thousand_cycles(&model(StiffnessBasis::Displacement));
    assert!(rec.v_end[9_999] > 0.1, "v = {} m", rec.v_end[9_999]);
    assert!(rec.e_lowest < 0.0);
}

#[test]
fn ten_thousand_cycles_contraction_is_bounded_with_the_strain_reading() {
    // Issue 19: the closure of the default stays below (e0 − e_min)/(1 + e0)·t = 8 mm and
    // e ≥ e_min after every update (checked inside). Measured: v = 0.034 / 0.615 / 4.809 /
    // 7.735 / 7.976 mm after 1 / 10 / 100 / 1000 / 10 000 cycles; the largest cycle adds
    // 0.065 mm, cycle 100 0.027 mm, cycle 1000 2.9e-4 mm, cycle 10 000 2.4e-6 mm; lowest e
    // 0.15030.
    let m = strain_model();
    let rec = ten_thousand_cycles(&m);
    let bound = closure_bound(&m);
    let per_cycle: Vec<f64> = std::iter::once(rec.v_end[0])
        .chain(rec.v_end.windows(2).map(|w| w[1] - w[0]))
        .collect();
    let largest = per_cycle.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    println!(
        "bounded 10 000 cycles: bound {:.3} mm, largest per-cycle {:.4} mm, cycle 100 {:.2e} mm, \
         cycle 1000 {:.2e} mm, cycle 10 000 {:.2e} mm",
        bound / MM,
        largest / MM,
        per_cycle[99] / MM,
        per_cycle[999] / MM,
        per_cycle[9_999] / MM
    );
    let total = rec.v_end[9_999];
    assert!(total < bound, "total {total} m within the bound {bound} m");
    assert!(total > 0.9 * bound, "the cycles use the reserve: {total} m");
    assert!(largest < 0.08 * MM, "per-cycle contraction {largest} m");
    assert!(per_cycle[999] < 1e-3 * MM && per_cycle[9_999].abs() < 1e-5 * MM);
    assert!(rec.e_lowest >= m.params.e_min && rec.state.void_ratio < m.params.e_min + 0.01);
}

#[test]
fn numerical_tangent_is_consistent_with_large_increments() {
    for basis in [StiffnessBasis::Displacement, StiffnessBasis::Strain] {
        let m = GpInterface::new(GpInterfaceParams {
            tangent: TangentChoice::Numerical,
            ..legacy_params(basis)
        })
        .expect("valid");
        let mut st = m.init_state(200.0 * KPA).expect("init");
        for _ in 0..10 {
            st = m
                .update(&st, &Local3::new(0.3 * MM, 0.1 * MM, 0.0))
                .expect("pre")
                .state;
        }
        // Large increments: further loading, and a reversal with an axial component.
        for inc in [
            Local3::new(2.0 * MM, 0.5 * MM, 0.02 * MM),
            Local3::new(-1.5 * MM, 0.8 * MM, -0.01 * MM),
        ] {
            let up = m.update(&st, &inc).expect("base");
            assert_eq!(up.kind, TangentKind::Consistent);
            let h = 1e-6 * inc.norm();
            let mut fd = Tangent3::zeros();
            for j in 0..3 {
                let (mut dp, mut dm) = (inc, inc);
                dp[j] += h;
                dm[j] -= h;
                let tp = GpInterface::traction(&m.update(&st, &dp).expect("+").state);
                let tm = GpInterface::traction(&m.update(&st, &dm).expect("-").state);
                fd.set_column(j, &((tp - tm) / (2.0 * h)));
            }
            let err = (fd - up.tangent).norm() / up.tangent.norm();
            // The continuum tangent of the same update, for comparison.
            let cont = model(basis).update(&st, &inc).expect("continuum").tangent;
            let err_c = (fd - cont).norm() / cont.norm();
            println!("{basis:?} increment {inc:?}: numerical tangent error {err:.2e}, continuum {err_c:.2e}");
            assert!(err < 1e-3, "consistent tangent vs central FD: {err}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Property tests

/// A random shear path from activation (steps of up to ±0.5 mm, normal jump fixed or small);
/// the first failure of the update is returned.
fn try_run_path(
    m: &GpInterface,
    sn: f64,
    path: &[(f64, f64, f64)],
) -> Result<GpInterfaceState, MaterialError> {
    let mut st = m.init_state(sn)?;
    for &(a, b, c) in path {
        st = m.update(&st, &Local3::new(a, b, c))?.state;
    }
    Ok(st)
}

/// Two neutral-loading paths (found by the property tests: σ_n = 259 kPa with a small opening
/// in the last step, and σ_n = 504 kPa) on which `reversal_branch = start` exhausts NMAX = 10000
/// attempts (at T = 0.254 and T = 0.062 of a step).
///
/// The mechanism (the same on both paths): every substep starts on the unloading side, so the
/// reversal rule (spec (I18)) moves the reversal point to the start; the re-mapped indicator
/// nᵀdσe/(|n||dσe|) at the start stays just on the unloading side (−2.1e-4 and −8.2e-5, beyond
/// tolN = 1e-6). At the end of the substep, away from the new reversal point, the indicator is
/// loading (+4.3e-2 after dT = 5.5e-2 on the 259 kPa path). The linear change-point estimate
/// retries at 2.7e-4 (still loading, +9.2e-3), then at 6.1e-6, where the indicator has not
/// moved: that substep is taken as unloading, and the next one starts on the unloading side
/// again with the reversal point moved along, so the integration creeps on by about 6e-6 per
/// three attempts. The default `reversal_branch = trial` reads (I18) again at the substep's
/// trial point, so a reversal at a substep's start is followed by reverse loading where the
/// substep moves into loading, and both paths are followed with few substeps.
#[test]
fn neutral_loading_path_does_not_stall() {
    for m in [
        GpInterface::new(GpInterfaceParams::default()).expect("the default"),
        strain_model(),
    ] {
        neutral_loading_paths_are_followed(&m);
    }
}

/// Follows both neutral-loading paths with `m` in few substeps.
fn neutral_loading_paths_are_followed(m: &GpInterface) {
    assert_eq!(m.params.reversal_branch, ReversalBranch::Trial);
    for (sn, path) in neutral_loading_paths() {
        let mut st = m.init_state(sn).expect("initial state");
        for &(a, b, c) in &path {
            let up = m
                .update(&st, &Local3::new(a, b, c))
                .expect("the path is followed");
            assert!(up.substeps < 1000, "σ_n = {sn}: {} substeps", up.substeps);
            st = up.state;
        }
        assert!(st.stress[2] >= 0.0, "σ_n = {sn}: {:?}", st.stress);
    }
}

/// One increment of the local jump (δ_s, δ_a, δ_n), m.
type JumpIncrement = (f64, f64, f64);

/// The two shear paths (σ_n, jump increments) on which every substep starts just on the
/// unloading side: the σ_n = 504 kPa path of stop 9 and the σ_n = 259 kPa path of stop 7.
fn neutral_loading_paths() -> [(f64, [JumpIncrement; 4]); 2] {
    [
        (
            503885.0626318813,
            [
                (
                    0.0002823137999374797,
                    -0.00034001435851375257,
                    -1.861295868447405e-5,
                ),
                (-0.00020079605854873286, -0.0002908102213202816, 0.0),
                (-0.00018816857876200342, -0.00043587505530124813, 0.0),
                (-0.0003640664568879537, 7.970093471808418e-5, 4.007363672632822e-6),
            ],
        ),
        (
            259036.34646792398,
            [
                (0.00048773549590428757, -0.0004894314795968731, 0.0),
                (-3.230506722188435e-5, -0.0002458453170008869, 0.0),
                (0.00045181820854828486, -0.00041808217241905203, 0.0),
                (
                    -0.0002565386355542881,
                    -0.00018389384952658937,
                    9.269831003934147e-6,
                ),
            ],
        ),
    ]
}

/// The other reading, `reversal_branch = start`, kept as an option: it stalled on both paths of
/// [`neutral_loading_path_does_not_stall`] with the legacy stiffness reading, where the paths
/// were found, creeping on by DT_MIN per few attempts, until the integrator located at most
/// MAX_BRANCH_FLIPS branch flips per step (module docs of `gp_integrator`). Both readings now
/// follow both paths with either stiffness reading, and they agree on a path without reversals
/// (virgin shear at constant σ_n).
#[test]
fn start_reading_follows_the_neutral_loading_paths() {
    let with = |base: GpInterfaceParams, branch: ReversalBranch| {
        GpInterface::new(GpInterfaceParams {
            reversal_branch: branch,
            ..base
        })
        .expect("valid parameters")
    };
    for base in [legacy_params(StiffnessBasis::Displacement), strain_params()] {
        let start = with(base.clone(), ReversalBranch::Start);
        let trial = with(base, ReversalBranch::Trial);
        for (sn, path) in neutral_loading_paths() {
            try_run_path(&start, sn, &path).expect("`start` follows the path");
            try_run_path(&trial, sn, &path).expect("`trial` follows the path");
        }
        let virgin = [(2.0e-4, 0.0, 0.0); 5];
        let a = try_run_path(&start, 300.0e3, &virgin).expect("virgin shear");
        let b = try_run_path(&trial, 300.0e3, &virgin).expect("virgin shear");
        assert_eq!(a.stress, b.stress);
    }
}

fn states_close(a: &GpInterfaceState, b: &GpInterfaceState, rel: f64) -> bool {
    let va = serde_json::to_value(a).expect("value");
    let vb = serde_json::to_value(b).expect("value");
    fn walk(x: &serde_json::Value, y: &serde_json::Value, rel: f64) -> bool {
        use serde_json::Value as V;
        match (x, y) {
            (V::Number(p), V::Number(q)) => {
                let (p, q) = (p.as_f64().unwrap_or(f64::NAN), q.as_f64().unwrap_or(f64::NAN));
                (p - q).abs() <= rel * p.abs().max(q.abs())
            }
            (V::Array(p), V::Array(q)) => p.len() == q.len() && p.iter().zip(q).all(|(p, q)| walk(p, q, rel)),
            (V::Object(p), V::Object(q)) => {
                p.len() == q.len() && p.iter().all(|(k, v)| q.get(k).is_some_and(|w| walk(v, w, rel)))
            }
            _ => x == y,
        }
    }
    walk(&va, &vb, rel)
}

fn path_strategy() -> impl Strategy<Value = Vec<(f64, f64, f64)>> {
    prop::collection::vec((-5e-4..5e-4_f64, -5e-4..5e-4_f64, -2e-5..1e-5_f64), 1..12)
}

fn rotate_state(st: &GpInterfaceState, c: f64, s: f64) -> GpInterfaceState {
    let rot = |v: [f64; 3]| [c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]];
    let mut q = st.clone();
    q.stress = rot(st.stress);
    q.strain = rot(st.strain);
    q.jump = rot(st.jump);
    q.plastic_strain = rot(st.plastic_strain);
    let r = st.reversal_point;
    q.reversal_point = [c * r[0] - s * r[1], s * r[0] + c * r[1]];
    q
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 48,
        failure_persistence: crate::test_support::proptest_persistence(),
        ..ProptestConfig::default()
    })]

    #[test]
    fn prop_update_is_pure_and_state_round_trips(path in path_strategy(), sn in 20e3..800e3_f64) {
        let m = strain_model();
        // every path is followed with the default `reversal_branch = trial`
        let st = try_run_path(&m, sn, &path).expect("the path is followed");
        let d = Local3::new(1e-4, -3e-5, 1e-6);
        let a = m.update(&st, &d).expect("a");
        let b = m.update(&st, &d).expect("b");
        prop_assert_eq!(&a, &b);
        let json = serde_json::to_string(&a.state).expect("serialize");
        let back: GpInterfaceState = serde_json::from_str(&json).expect("deserialize");
        // serde_json's default float parser may differ from the printed value by one ulp.
        prop_assert!(states_close(&back, &a.state, 4.0 * f64::EPSILON), "{:?} vs {:?}", back, a.state);
        prop_assert!(back.stress[2] >= 0.0);
    }

    #[test]
    fn prop_invariance_under_rotation_of_shear_axes(path in path_strategy(), th in 0.0..std::f64::consts::TAU, sn in 50e3..600e3_f64) {
        let m = strain_model();
        let (c, s) = (th.cos(), th.sin());
        let st = try_run_path(&m, sn, &path).expect("the path is followed");
        let rpath: Vec<(f64, f64, f64)> = path.iter().map(|&(a, b, n)| (c * a - s * b, s * a + c * b, n)).collect();
        let rst = try_run_path(&m, sn, &rpath).expect("the rotated path is followed");
        let expect = rotate_state(&st, c, s);
        let scale = sn.max(st.stress[2]);
        for i in 0..3 {
            prop_assert!((rst.stress[i] - expect.stress[i]).abs() < 1e-6 * scale,
                "stress {}: {} vs {}", i, rst.stress[i], expect.stress[i]);
        }
        prop_assert!((rst.void_ratio - expect.void_ratio).abs() < 1e-9);
        prop_assert!((rst.eta_max - expect.eta_max).abs() < 1e-7);
    }

    #[test]
    fn prop_continuum_tangent_matches_finite_differences(
        u0 in 0.5e-3..8e-3_f64, ratio in -0.5..0.5_f64, sn in 50e3..600e3_f64, dir in 0.0..std::f64::consts::TAU,
        which in 0..3_usize) {
        // the legacy readings and the default
        let m = match which {
            0 => model(StiffnessBasis::Displacement),
            1 => model(StiffnessBasis::Strain),
            _ => strain_model(),
        };
        // A virgin state sheared along a direction, then a tiny loading increment along it
        // (one substep: the update is a smooth function of the increment).
        let (c, s) = (dir.cos(), dir.sin());
        let mut st = m.init_state(sn).expect("init");
        for _ in 0..20 {
            st = m.update(&st, &Local3::new(c * u0 / 20.0, s * u0 / 20.0, 0.0)).expect("pre").state;
        }
        let h0 = 1e-7;
        let base = Local3::new(c * h0, s * h0, ratio * h0);
        let up = m.update(&st, &base).expect("base");
        prop_assert_eq!(up.kind, TangentKind::Continuum);
        let eps = 1e-10;
        let mut fd = Tangent3::zeros();
        for j in 0..3 {
            let mut dp = base;
            dp[j] += eps;
            let mut dm = base;
            dm[j] -= eps;
            let tp = GpInterface::traction(&m.update(&st, &dp).expect("+").state);
            let tm = GpInterface::traction(&m.update(&st, &dm).expect("-").state);
            fd.set_column(j, &((tp - tm) / (2.0 * eps)));
        }
        let err = (fd - up.tangent).norm() / up.tangent.norm();
        prop_assert!(err < 1e-3, "relative tangent error {} (FD {} vs {})", err, fd, up.tangent);
    }

    #[test]
    fn prop_void_ratio_never_falls_below_e_min(
        steps in prop::collection::vec((-5e-4..5e-4_f64, -5e-4..5e-4_f64, -1.0..1.0_f64), 1..25),
        sn0 in 20e3..2e6_f64) {
        // Random CNL paths of the default: shear steps of up to ±0.5 mm on both axes, each
        // followed by a change of σ_n by a factor e^±1 (within 20 kPa … 3 MPa) in steps of at
        // most 5 % of ln σ_n; e ≥ e_min after every step (checked by the driver) and the
        // closure within the bound.
        let m = strain_model();
        let run = |m: &GpInterface| -> Result<Vec<GpInterfaceState>, MaterialError> {
            let mut d = Driver::new(m, sn0, 0.0);
            let mut states = Vec::new();
            for &(us, ua, log_factor) in &steps {
                d.step(us, ua)?;
                let target = (d.st.stress[2] * log_factor.exp()).clamp(20e3, 3e6);
                let n = ((target / d.st.stress[2]).ln().abs() / 0.05).ceil().max(1.0) as usize;
                d.normal_to(target, n)?;
                states.push(d.st.clone());
            }
            Ok(states)
        };
        // A path the integrator cannot follow is not a case of this property: normal unloading
        // under shear can leave |τ|/σ_n above the peak ratio, and a reversal or closure from
        // there exhausts NMAX in every reading (measured on 400 such paths: 34 fail with the
        // default, 34 without the bound, 44 with the legacy reading; module docs, "Findings").
        let states = run(&m);
        prop_assume!(states.is_ok(), "path beyond the integrator: {:?}", states.as_ref().err());
        for st in states.expect("checked") {
            prop_assert!(st.void_ratio >= m.params.e_min, "e = {}", st.void_ratio);
            prop_assert!(st.v_mat < closure_bound(&m));
        }
    }
}

#[test]
fn if1_closure_at_400_and_800_kpa_is_bounded_with_the_default() {
    // Issue 19, acceptance 1, the default reading (`normal_basis: displacement`,
    // `void_ratio_bound: bandis`): measured 6.927 / 7.076 mm at 400 / 800 kPa, e = 0.1616 at the
    // end, against the bound 8 mm; the legacy reading (the same without the bound) 59.2 / 71.6
    // mm.
    let m = GpInterface::new(GpInterfaceParams::default()).expect("valid");
    assert_eq!(
        (m.params.normal_basis, m.params.void_ratio_bound),
        (StiffnessBasis::Displacement, VoidRatioBound::Bandis)
    );
    let (v400, v800, e800) = if1_closures(&m);
    let open = opening_from_100_kpa(&m);
    println!(
        "IF-1 default: closure {:.3} / {:.3} mm at 400 / 800 kPa, e = {e800:.4}; opens from 100 kPa after {:.3} mm; bound {:.3} mm",
        v400 / MM,
        v800 / MM,
        open / MM,
        closure_bound(&m) / MM
    );
    assert!(v400 > 6.7 * MM && v400 < 7.2 * MM, "v(400 kPa) = {v400}");
    assert!(v800 > v400 && v800 < 7.3 * MM, "v(800 kPa) = {v800}");
    assert!(v800 < closure_bound(&m) && e800 > m.params.e_min);
}

#[test]
fn ten_thousand_cycles_contraction_is_bounded_with_the_default() {
    // Issue 19: the default's closure stays below the bound and e ≥ e_min after every update
    // (checked inside [`ten_thousand_cycles`]).
    let m = GpInterface::new(GpInterfaceParams::default()).expect("valid");
    let rec = ten_thousand_cycles(&m);
    let bound = closure_bound(&m);
    let per_cycle: Vec<f64> = std::iter::once(rec.v_end[0])
        .chain(rec.v_end.windows(2).map(|w| w[1] - w[0]))
        .collect();
    let largest = per_cycle.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let at = |n: usize| rec.v_end[n - 1] / MM;
    println!(
        "default, 10 000 cycles: v = {:.3} / {:.3} / {:.3} / {:.3} / {:.3} mm after 1 / 10 / 100 / 1000 / 10 000 cycles; \
         largest per-cycle {:.4} mm, cycle 10 000 {:.2e} mm; lowest e {:.5}; bound {:.3} mm",
        at(1),
        at(10),
        at(100),
        at(1000),
        at(10_000),
        largest / MM,
        per_cycle[9_999] / MM,
        rec.e_lowest,
        bound / MM
    );
    assert!(rec.v_end[9_999] < bound, "within the bound {bound} m");
    assert!(rec.e_lowest >= m.params.e_min);
    assert!(
        per_cycle[9_999].abs() < 1e-3 * MM,
        "cycle 10 000 adds {} m",
        per_cycle[9_999]
    );
}

/// The points on which the coarse seed GP-interface quake stopped (issue 18: `interface_3`
/// near the left bank at el. 2840 m, t = 3.87 s; states and increments dumped from the run),
/// all past the peak (η ≈ η_max ≈ 1.09, cyclic branch). The loading direction turns within a
/// small fraction of every substep: a reversal at each start whose trial reads loading while
/// stage 1 softens back behind the new reversal point, or the indicator crossing zero again
/// after 10⁻⁴ of the step. Locating every flip, the integrator failed on each of these steps
/// at NMAX = 10,000 attempts (T = 0.69, 0.99, 0.64, 0.27); with at most MAX_BRANCH_FLIPS
/// located per step they take at most 764 substeps (module docs of `gp_integrator`).
#[test]
fn reversals_past_the_peak_do_not_stall_the_substepping() {
    // The states come from the quake run without the stress-ratio cap (η up to 1.09, above
    // η_p ≈ 1.03), so they are replayed with that reading.
    let m = GpInterface::new(GpInterfaceParams {
        stress_ratio_cap: StressRatioCap::None,
        ..GpInterfaceParams::default()
    })
    .expect("the default without the cap");
    let cases = [
        (
            GpInterfaceState {
                stress: [-6921.657664536962, -43426.203671249496, 40446.709595595305],
                strain: [-0.22935571305306307, -0.217106924487507, 0.06342183096657386],
                jump: [-0.022935571305306407, -0.02171069244875075, -0.006342183096657433],
                plastic_strain: [-0.19504521822914073, -0.02332912132880077, -0.005322061037415226],
                v_mat: 0.0063421830966573865,
                void_ratio: 0.17072271129178268,
                reversal_point: [-0.17113382772538765, -1.0736683892465149],
                eta_max: 1.0879165289165946,
                sigma_c_max: 279201.9153331829,
                plastic_work: 14897.580381237112,
                delta_e_c: 0.0005945228204369789,
                branch: GpBranch::Cyclic,
                open: false,
                w_open: 0.0,
                gap: 0.0,
                g_frozen: 4.683753385137379e-17,
            },
            Local3::new(
                -1.092883848626871e-7,
                -8.208298064599912e-7,
                -1.5673449906812653e-9,
            ),
        ),
        (
            GpInterfaceState {
                stress: [-11522.992798142093, -41033.30153885214, 40130.12532441561],
                strain: [-0.22341953772314174, -0.18141402859375014, 0.0634211423309015],
                jump: [-0.022341953772314148, -0.01814140285937523, -0.006342114233090099],
                plastic_strain: [-0.1733337870331852, 0.004152933164730808, -0.005291852557234026],
                v_mat: 0.006342114233090151,
                void_ratio: 0.17072357208637312,
                reversal_point: [-0.16892259001913412, -1.0778805921101364],
                eta_max: 1.0928802871295702,
                sigma_c_max: 279191.44641962054,
                plastic_work: 13540.657004792867,
                delta_e_c: 0.0005139621305678601,
                branch: GpBranch::Cyclic,
                open: false,
                w_open: 0.0,
                gap: 0.0,
                g_frozen: -5.204170427930421e-17,
            },
            Local3::new(
                -0.00033860733596023613,
                -0.0031205201147932946,
                -3.582997012478511e-6,
            ),
        ),
        (
            GpInterfaceState {
                stress: [-6933.514247226306, -43505.264118772706, 40418.53707660226],
                strain: [-0.22953286851079976, -0.21341671718851304, 0.06346077138450988],
                jump: [
                    -0.022953286851079946,
                    -0.021341671718851526,
                    -0.006346077138450938,
                ],
                plastic_strain: [-0.1951603557100905, -0.01938355060234632, -0.0052805045255030015],
                v_mat: 0.006346077138450989,
                void_ratio: 0.17067403576936263,
                reversal_point: [-0.16892259001913412, -1.0778805921101364],
                eta_max: 1.0928802871295702,
                sigma_c_max: 279191.44641962054,
                plastic_work: 14737.484774194416,
                delta_e_c: 0.0005849809642401001,
                branch: GpBranch::Cyclic,
                open: false,
                w_open: 0.0,
                gap: 0.0,
                g_frozen: -5.117434254131581e-17,
            },
            Local3::new(
                -2.0394744089515225e-5,
                -0.0014242497289745984,
                -1.5898950446281597e-6,
            ),
        ),
        (
            GpInterfaceState {
                stress: [-6828.026307452837, -43572.37285772641, 40423.59643958334],
                strain: [-0.22959044382591026, -0.21401507774729076, 0.06346204268411512],
                jump: [-0.02295904438259099, -0.021401507774729298, -0.006346204268411461],
                plastic_strain: [-0.19557528655118928, -0.019754572400204666, -0.005279721539523666],
                v_mat: 0.006346204268411513,
                void_ratio: 0.1706724466448561,
                reversal_point: [-0.16892259001913412, -1.0778805921101364],
                eta_max: 1.0928802871295702,
                sigma_c_max: 279191.44641962054,
                plastic_work: 14756.526515457837,
                delta_e_c: 0.0005861105199019196,
                branch: GpBranch::Cyclic,
                open: false,
                w_open: 0.0,
                gap: 0.0,
                g_frozen: -5.204170427930421e-17,
            },
            Local3::new(
                -3.093135733802366e-6,
                -2.9067431399265944e-5,
                -6.30039534114271e-8,
            ),
        ),
    ];
    for (prev, d) in &cases {
        for scale in [1.0, 0.5, 0.1] {
            let up = m.update(prev, &(d * scale)).expect("the step is integrated");
            assert!(up.substeps < 1000, "scale {scale}: {} substeps", up.substeps);
            assert_ne!(up.state.branch, GpBranch::Elastic, "scale {scale}: plastic");
        }
    }
}

/// Ratio |τ|/σ̂_n over the peak ratio η_p(ψ) (spec (I9)) of a state.
fn peak_fraction(m: &GpInterface, st: &GpInterfaceState) -> f64 {
    let psi = m.state_parameter(st.stress[2], st.void_ratio, st.delta_e_c);
    m.stress_ratio(&st.stress).norm() / m.peak_ratio(psi)
}

/// Cyclic shear of ±5 mm with σ_n cycling 200 → 40 → 200 kPa in phase (80 steps per cycle),
/// the crest's path under the quake: the largest η/η_p over the run, and the first failure.
fn shear_with_normal_unloading(m: &GpInterface, cycles: usize) -> (f64, Option<MaterialError>) {
    let mut d = Driver::new(m, 200.0 * KPA, 0.0);
    let mut worst = 0.0_f64;
    for _ in 0..cycles {
        for i in 0..80 {
            let phase = 2.0 * std::f64::consts::PI * i as f64 / 80.0;
            d.sigma_ref = 120.0 * KPA + 80.0 * KPA * phase.cos();
            let du = 5.0 * MM * 2.0 * std::f64::consts::PI / 80.0 * phase.cos();
            if let Err(e) = d.step(du, 0.0) {
                return (worst, Some(e));
            }
            worst = worst.max(peak_fraction(m, &d.st));
        }
    }
    (worst, None)
}

#[test]
fn stress_ratio_stays_on_the_peak_circle_under_cyclic_unloading() {
    // Issue 18: cyclic reloading maps onto the max-history circle and does not see the peak
    // circle; with σ_n falling while the shear reloads, η of the seed's equations grows to
    // 6.7·η_p (measured) and the substepping stalls at NMAX. The cap keeps every state inside.
    let uncapped = GpInterface::new(GpInterfaceParams {
        stress_ratio_cap: StressRatioCap::None,
        ..GpInterfaceParams::default()
    })
    .expect("valid");
    let (worst, failure) = shear_with_normal_unloading(&uncapped, 20);
    println!("no cap: largest η/η_p {worst:.3}, failure {failure:?}");
    assert!(
        worst > 2.0 || failure.is_some(),
        "the defect the cap is for: {worst}"
    );

    let m = GpInterface::new(GpInterfaceParams::default()).expect("valid");
    let (worst, failure) = shear_with_normal_unloading(&m, 20);
    println!("peak cap: largest η/η_p {worst:.12}");
    assert!(failure.is_none(), "{failure:?}");
    assert!(worst <= 1.0 + 1e-9, "η/η_p = {worst}");
    assert!(worst > 1.0 - 1e-9, "the path reaches the cap: {worst}");
}

#[test]
fn tangent_on_the_cap_follows_the_update() {
    // A point reloaded onto the peak circle at falling σ_n: the continuum tangent with the
    // cap's Jacobian (`capped_tangent`) against central differences of the update. Measured:
    // 1.0 % off with the Jacobian, 58 % with D^ep alone (its shear row misses η_p·dσ_n).
    let m = GpInterface::new(GpInterfaceParams::default()).expect("valid");
    let mut d = Driver::new(&m, 200.0 * KPA, 0.0);
    for _ in 0..40 {
        d.step(0.2 * MM, 0.0).expect("shear");
    }
    d.normal_to(60.0 * KPA, 20).expect("normal unloading");
    let inc = Local3::new(0.05 * MM, 0.0, 0.002 * MM);
    let up = m.update(&d.st, &inc).expect("base");
    assert!(peak_fraction(&m, &up.state) > 1.0 - 1e-9, "on the cap");
    assert_eq!(up.state.branch, GpBranch::Cyclic);
    let h = 1e-6 * inc.norm();
    let mut fd = Tangent3::zeros();
    for j in 0..3 {
        let (mut dp, mut dm) = (inc, inc);
        dp[j] += h;
        dm[j] -= h;
        let tp = GpInterface::traction(&m.update(&d.st, &dp).expect("+").state);
        let tm = GpInterface::traction(&m.update(&d.st, &dm).expect("-").state);
        fd.set_column(j, &((tp - tm) / (2.0 * h)));
    }
    let err = (fd - up.tangent).norm() / fd.norm();
    println!(
        "capped tangent {:?}\ncentral differences {fd:?}\nerror {err:.3e}",
        up.tangent
    );
    assert!(err < 0.05, "tangent on the cap: {err}");
}
