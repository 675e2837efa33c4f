//! Mesh partitioning for cfrd.
