//! Conventions used everywhere in cfrd (documentation only).
//!
//! # Units
//! SI throughout: N, m, kg, s, Pa. Scenes and outputs are SI. The model spec writes the
//! constitutive equations in kPa; a model that is coded in kPa converts at its boundary, once.
//!
//! # Axes
//! `x` = stream direction (upstream → downstream), `y` = dam axis, `z` = up; gravity is −z.
//! The seed's figures use X stream, Y vertical, Z dam axis: the seed's Y is our z and its Z is
//! our y. Output that reproduces a seed figure says which axis it plots.
//!
//! # Signs
//! Tension positive for stress and strain in all code. Geotechnical, compression-positive
//! quantities (p, q, η, an interface's σ_n, closure) are produced by one named function each
//! and carry the convention in their names or docs.
//!
//! # Voigt order
//! `[xx, yy, zz, xy, yz, zx]`; strain-like vectors carry engineering shear γ = 2ε
//! ([`crate::tensor`]).
//!
//! # Interface frame
//! Local frame `[s, a, n]` (spec §5.2): `n` points from the slab (face B) into the cushion
//! (face A), `a` is the dam axis projected on the face, `s = a × n` points up the slope.
//! The jump is δ = u_A − u_B (cushion relative to slab); δ_n > 0 is opening. The traction
//! T = (τ_s, τ_a, t_n) is work-conjugate to δ, so t_n = −σ_n is tension positive.
//!
//! # Numbering
//! 0-based indices in code. Input ids (node and element ids of the mesh file) are kept and
//! written to the results, which are always in input order, whatever the rank count.
//!
//! # Glossary of short names allowed inside kernels
//! `sig` stress, `eps` strain, `d_eps` step increment Δ, `corr_u` Newton correction δu,
//! `dd_e` elastic D, `h_l`/`h_u` loading/unloading plastic moduli, `gamma`/`beta` Newmark.
