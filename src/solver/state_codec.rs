//! Binary encoding of the committed integration-point states of one element, for checkpoints.
//!
//! The committed states of element `e` of a block (its 8 Gauss points for a hexahedron, its 4
//! points for an interface or joint element, spec (E8)) are encoded as one `postcard` message:
//! the slice of the model's `State` structs (their serde form). `f64` fields are stored as their
//! 8 little-endian IEEE bytes, so a decoded state is bitwise the one encoded; integers are
//! varints and enums variant indices. The encoding carries no field names, so it can only be
//! decoded by the same model: a checkpoint names the scene (by hash) it was written for.
//!
//! Decoding sets both the committed and the trial states of the element (after a converged step
//! they are equal, [`QpStore::commit`]).

use super::interface::InterfaceElements;
use super::qp_store::QpStore;
use super::solid::SolidBlock;
use crate::element::interface8::INTERFACE_POINTS;
use crate::element::quadrature::HEX_GAUSS_POINTS;
use serde::de::DeserializeOwned;
use serde::Serialize;

/// Encodes the committed states of points `per·e .. per·(e+1)`.
fn encode<S: Serialize>(store: &QpStore<S>, e: usize, per: usize) -> Result<Vec<u8>, String> {
    let states = store
        .committed
        .get(per * e..per * (e + 1))
        .ok_or_else(|| format!("no states for block-local element {e}"))?;
    postcard::to_allocvec(states).map_err(|err| format!("encoding the states: {err}"))
}

/// Decodes `bytes` into the committed and trial states of points `per·e .. per·(e+1)`.
fn decode<S: DeserializeOwned + Clone>(
    store: &mut QpStore<S>,
    e: usize,
    per: usize,
    bytes: &[u8],
) -> Result<(), String> {
    let states: Vec<S> =
        postcard::from_bytes(bytes).map_err(|err| format!("the stored states do not decode: {err}"))?;
    if states.len() != per {
        return Err(format!(
            "{} stored point states, the element has {per} points",
            states.len()
        ));
    }
    let range = per * e..per * (e + 1);
    if range.end > store.len() {
        return Err(format!("no states for block-local element {e}"));
    }
    store.committed[range.clone()].clone_from_slice(&states);
    store.trial[range].clone_from_slice(&states);
    Ok(())
}

/// The committed states of solid element `e` (block-local index), encoded.
pub fn encode_solid(block: &SolidBlock, e: usize) -> Result<Vec<u8>, String> {
    match block {
        SolidBlock::Elastic(ms) => encode(&ms.store, e, HEX_GAUSS_POINTS),
        SolidBlock::RockfillGp(ms) => encode(&ms.store, e, HEX_GAUSS_POINTS),
    }
}

/// Restores the committed (and trial) states of solid element `e` from [`encode_solid`]'s bytes.
pub fn decode_solid(block: &mut SolidBlock, e: usize, bytes: &[u8]) -> Result<(), String> {
    match block {
        SolidBlock::Elastic(ms) => decode(&mut ms.store, e, HEX_GAUSS_POINTS, bytes),
        SolidBlock::RockfillGp(ms) => decode(&mut ms.store, e, HEX_GAUSS_POINTS, bytes),
    }
}

/// The committed states of interface element `e` (block-local index), encoded.
pub fn encode_interface(block: &InterfaceElements, e: usize) -> Result<Vec<u8>, String> {
    match block {
        InterfaceElements::Hyperbolic(ls) => encode(&ls.store, e, INTERFACE_POINTS),
        InterfaceElements::MohrCoulomb(ls) => encode(&ls.store, e, INTERFACE_POINTS),
        InterfaceElements::Joint(ls) => encode(&ls.store, e, INTERFACE_POINTS),
        InterfaceElements::GpInterface(ls) => encode(&ls.store, e, INTERFACE_POINTS),
    }
}

/// Restores the committed (and trial) states of interface element `e` from
/// [`encode_interface`]'s bytes.
pub fn decode_interface(block: &mut InterfaceElements, e: usize, bytes: &[u8]) -> Result<(), String> {
    match block {
        InterfaceElements::Hyperbolic(ls) => decode(&mut ls.store, e, INTERFACE_POINTS, bytes),
        InterfaceElements::MohrCoulomb(ls) => decode(&mut ls.store, e, INTERFACE_POINTS, bytes),
        InterfaceElements::Joint(ls) => decode(&mut ls.store, e, INTERFACE_POINTS, bytes),
        InterfaceElements::GpInterface(ls) => decode(&mut ls.store, e, INTERFACE_POINTS, bytes),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::rockfill_gp::RockfillGpParams;
    use crate::material::SolidParams;

    fn gp_block(n: usize) -> SolidBlock {
        SolidBlock::new(&SolidParams::RockfillGp(RockfillGpParams::default()), n).unwrap()
    }

    #[test]
    fn rockfill_states_round_trip_bitwise() {
        let mut a = gp_block(3);
        let SolidBlock::RockfillGp(ms) = &mut a else {
            unreachable!()
        };
        // make element 1's states distinct from the initial ones, with awkward bit patterns
        for (k, s) in ms.store.committed[8..16].iter_mut().enumerate() {
            s.stress.0[0] = -1.0e5 / 3.0 - k as f64 * std::f64::consts::PI;
            s.stress.0[4] = f64::MIN_POSITIVE * (k + 1) as f64;
        }
        let bytes = encode_solid(&a, 1).unwrap();
        let mut b = gp_block(3);
        decode_solid(&mut b, 1, &bytes).unwrap();
        let (SolidBlock::RockfillGp(x), SolidBlock::RockfillGp(y)) = (&a, &b) else {
            unreachable!()
        };
        assert_eq!(x.store.committed[8..16], y.store.committed[8..16]);
        assert_eq!(y.store.trial[8..16], y.store.committed[8..16]);
        for (p, q) in x.store.committed[8..16].iter().zip(&y.store.committed[8..16]) {
            for c in 0..6 {
                assert_eq!(p.stress.0[c].to_bits(), q.stress.0[c].to_bits());
            }
        }
        // the other elements are untouched
        assert_eq!(y.store.committed[0], y.store.committed[16]);
        assert_ne!(y.store.committed[0], y.store.committed[8]);
    }

    #[test]
    fn interface_states_round_trip_bitwise() {
        use crate::material::interface_mc::MohrCoulombParams;
        use crate::material::InterfaceParams;
        let params = InterfaceParams::MohrCoulomb(MohrCoulombParams::default());
        let mut a = InterfaceElements::new(&params, 2, 1.0e5).unwrap();
        let InterfaceElements::MohrCoulomb(ls) = &mut a else {
            unreachable!()
        };
        for (k, s) in ls.store.committed[4..8].iter_mut().enumerate() {
            s.tau = [1.0 / 3.0 + k as f64, -2.0e-300];
            s.slipping = k % 2 == 1;
        }
        let bytes = encode_interface(&a, 1).unwrap();
        let mut b = InterfaceElements::new(&params, 2, 0.0).unwrap();
        decode_interface(&mut b, 1, &bytes).unwrap();
        let (InterfaceElements::MohrCoulomb(x), InterfaceElements::MohrCoulomb(y)) = (&a, &b) else {
            unreachable!()
        };
        assert_eq!(x.store.committed[4..8], y.store.committed[4..8]);
        assert_eq!(y.store.trial[4..8], y.store.committed[4..8]);
        assert!(y.store.committed[5].slipping && !y.store.committed[4].slipping);
        // 4 points per element: the 8 states of a hexahedron do not fit
        assert!(decode_interface(
            &mut b,
            0,
            &postcard::to_allocvec(&x.store.committed[0..8]).unwrap()
        )
        .is_err());
    }

    #[test]
    fn bad_bytes_are_an_error_not_a_panic() {
        let a = gp_block(1);
        let bytes = encode_solid(&a, 0).unwrap();
        let mut b = gp_block(1);
        assert!(decode_solid(&mut b, 0, &bytes[..bytes.len() / 2]).is_err());
        assert!(decode_solid(&mut b, 0, &[]).is_err());
        assert!(decode_solid(&mut b, 1, &bytes).is_err(), "element out of range");
        // states of another model (elastic, same point count) do not decode as rockfill states
        let el = SolidBlock::new(
            &SolidParams::Elastic(crate::material::elastic::ElasticParams {
                young: 1.0e8,
                poisson: 0.3,
                density: 2000.0,
            }),
            1,
        )
        .unwrap();
        let other = encode_solid(&el, 0).unwrap();
        assert!(decode_solid(&mut b, 0, &other).is_err());
        assert!(encode_solid(&a, 1).is_err());
    }
}
