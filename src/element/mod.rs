//! Element kernels: shape functions, quadrature and the element routines.

pub mod hex8;
pub mod hex8_modes;
pub mod interface8;
pub mod interface_frame;
pub mod quadrature;
pub mod shape;
