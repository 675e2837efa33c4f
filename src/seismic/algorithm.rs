//! How `cfrd accel` generates a spectrum-compatible artificial accelerogram (documentation
//! only). Section and step numbers refer to the seismic spec (`shared/spec/seismic.md`).
//!
//! # Target (spec §1)
//! Sa(T) = a·β(T), β of DL 5073-2000 / NB 35047-2015 ([`super::spectrum`], §1.1): rising
//! branch 1 → βmax on [0, 0.1] s, plateau to Tg, decay βmax·(Tg/T)^γ to 3 s, floor 0.2·βmax;
//! γ = 0.9 (DL 5073-2000, the seed's code) or 0.6 (NB 35047-2015), overridable. The vertical
//! target is the same shape scaled by a_v = 2/3·a_h (§1.1) unless the PGA is given per
//! component.
//!
//! # One component ([`super::generator`], §2.2)
//! 1. **Frequencies** (step 1): N = ⌈60·f_hi⌉ cosines uniformly spaced on [f_lo, f_hi]
//!    (0.2–40 Hz at dt = 0.01 s).
//! 2. **Target PSD** (step 2), Kaul/Vanmarcke: S(ω) = (ζ/(πω))·Sa(ω)² / (−ln[−(π/(ωT_d))·ln(1 − r)]),
//!    T_d = t2 − t1, r = 0.15. The input is checked so that the logarithm's argument stays in (0, 1).
//! 3. **Series** (steps 3–4): a(t) = f(t)·Σ A_k·cos(ω_k·t + φ_k), A_k = √(4·S(ω_k)·Δω), phases
//!    uniform on [0, 2π) from a ChaCha20 stream; f(t) the Jennings–Housner–Tsai envelope
//!    ((t/t1)², 1, exp(−c·(t − t2))).
//! 4. **Every iterate is finished** before it is scored (steps 7–8, [`super::correction`]):
//!    - zero-phase high-pass with the 4th-order Butterworth magnitude 1/√(1 + (f_c/f)⁸),
//!      f_c = 0.05 Hz, applied by FFT with 20 s of zero padding;
//!    - a half-cosine taper over the first and last 0.5 s (the acausal FFT operations spread
//!      into t = 0);
//!    - end-condition baseline correction: subtract f(t)·(α + β·t/T) with α, β such that the end
//!      velocity and displacement are zero (the "low-order" variant of step 8);
//!    - PGA by local peak adjustment, not scaling (step 7): the largest peak t_p is multiplied
//!      through 1 + (k − 1)·exp(−(t − t_p)²/(2σ²)), k = a_p/|a(t_p)|, σ = 2·dt;
//!    - the last two alternate until the end velocity is below 1e-7 m/s and the end
//!      displacement below 1e-6 m, ending on the peak adjustment, so the PGA is exact.
//! 5. **Score** (step 5): the 5 %-damped pseudo-acceleration spectrum ([`super::response`]:
//!    Nigam–Jennings exact recurrence, ≥ 5 s of trailing zeros, sub-steps below 10·dt, Hermite
//!    peak between samples) at 300 control periods log-spaced on [0.025, 3] s (1.6 % apart).
//!    The score is the largest |Sa/target − 1| at the control periods ≥ 0.04 s; the best
//!    iterate is kept, and the iterations stop once the score is ≤ 3 %.
//! 6. **FFT spectral-ratio correction** (step 6), the first 20 iterations: the FFT of the
//!    finished record is multiplied by R(f) = target/Sa interpolated in log T, constant beyond
//!    both ends of the control range (not 1), and transformed back. This is the spec's
//!    alternation of FFT correction and peak adjustment (step 7).
//! 7. **Wavelet correction** ([`super::wavelet`]), the next 20 iterations. Step 6 alone stalls
//!    at 5–16 % for a single record (§2.4; here 7–11 % on the dense control grid): a smooth
//!    amplitude gain cannot remove the period-to-period jaggedness that comes from the phases.
//!    At the extrema in period of the error, tapered-cosine wavelets are added where each
//!    oscillator peaks in time (Lilhanand & Tseng 1988; Abrahamson 1992; Al Atik & Abrahamson
//!    2010), amplitudes from the linear system of the responses at the peak times, Tikhonov
//!    regularized (λ = 0.1) and under-relaxed (0.8). When a response is too high, the other
//!    peaks above the target are constrained too (at most 4 per period), so that another cycle
//!    does not take over.
//!
//! # Three components (step 9)
//! x, y, z use streams 0, 1, 2 of ChaCha20 keyed by the record's seed (`seed_from_u64`):
//! independent, platform-independent phase sets from one seed. FFTs use `rustfft`'s scalar
//! planner, so the bytes of a record do not depend on the CPU's SIMD features (the
//! transcendental functions come from the platform's libm).
//!
//! # Acceptance (spec §2.3)
//! 60 periods log-spaced on [0.04, 3] s, different from the control periods: every
//! |Sa/target − 1| ≤ 10 %, mean ≤ 5 %, PGA = target to 0.1 %
//! ([`super::generator::ComponentReport::accepted`]).
//!
//! # Measured: the seed record
//! `inputs/accel/seed_quake.yaml` (DL 5073-2000, βmax 1.6, Tg 0.20 s, γ 0.9; 20 s at 0.01 s;
//! PGA 3 / 3 / 2 m/s²; envelope 2 s, 12 s, 0.35; seed 2015), measured with
//! `cfrd accel inputs/accel/seed_quake.yaml -o out/accel` at commit `20a8b33` (generator of
//! `c41dcc1`):
//!
//! | axis | PGA (target) m/s² | mean error | max error | range | PGV m/s | PGD m | end v m/s |
//! |---|---|---|---|---|---|---|---|
//! | x | 3.000 (3.0) | 1.45 % | 5.89 % | −3.86 … +5.89 % | 0.186 | 0.159 | 1.5e-8 |
//! | y | 3.000 (3.0) | 1.28 % | 5.08 % | −5.08 … +2.29 % | 0.211 | 0.273 | 4.8e-8 |
//! | z | 2.000 (2.0) | 1.36 % | 5.35 % | −5.35 … +4.33 % | 0.151 | 0.076 | 4.0e-8 |
//!
//! Correlations: xy −0.083, yz −0.086, zx +0.087. Kept iterates: 28, 40, 34 of 40 (all three
//! in the wavelet phase). Generation takes about 6 s for the three components (one core).
//!
//! **Known limitation**: apart from its largest peak, a record matching this narrow spectrum
//! (Tg 0.20 s, γ 0.9) peaks at only about 0.5–0.7·a_h, so the local peak adjustment makes the PGA one short
//! pulse (σ = 0.02 s) well above the next-largest peak (x 3.0 vs 2.14, y 3.0 vs 1.54, z 2.0 vs
//! 1.19 m/s²). The spectrum accounts for it (the pulse is part of every scored iterate), but
//! an FE mesh that transmits only up to ≈ 5 Hz (spec §3.4) will not see the full PGA.
//!
//! The unit tests (`cargo test --no-default-features --lib --release seismic`) check the same
//! record at the 60 acceptance periods and at 200 further periods on [0.04, 3] s.
//!
//! # References
//! Gasparini, D. A. & Vanmarcke, E. H. (1976). SIMQKE: a program for artificial motion
//! generation. MIT, Dept. of Civil Engineering.
//! Jennings, P. C., Housner, G. W. & Tsai, N. C. (1969). Simulated earthquake motions for design
//! purposes. Proc. 4th WCEE, A-1, 145–160.
//! Nigam, N. C. & Jennings, P. C. (1969). Calculation of response spectra from strong-motion
//! earthquake records. Bull. Seismol. Soc. Am. 59(2), 909–922.
