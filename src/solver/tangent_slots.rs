//! Where the element matrices go in the tangent's storage: the element loop adds every entry
//! of K_e straight into PETSc's compressed rows ([`crate::linalg::petsc::CsrLayout`]) instead
//! of calling `MatSetValues`, which searches each row's columns for every entry of every
//! element (issue 20: some 8 % of a medium seed scene's run).
//!
//! The pattern is made once with every element (`Model::preallocate_pattern`) and holds whole
//! 3 × 3 node blocks: the three rows of a node have the same columns, and the three columns of
//! a node are adjacent in every row. So one offset per node pair (a, b) of an element finds
//! its nine entries: entry (3a + i, 3b + j) is at `rows[3·r_a + i] + offset + j` of the block
//! (diagonal or off-diagonal) that holds node b's columns, r_a being node a's owned position.
//! Each entry is still summed over the same elements in the same order as before, from zero,
//! so the tangent is the same bit for bit (and so at any rank count, module docs of
//! `discretization`).

use super::discretization::Discretization;
use super::solid::Matrix24;
use crate::linalg::petsc::CsrLayout;

/// Flag of an offset into the off-diagonal block.
const OFF: u32 = 1 << 31;

/// Node rows owned by another rank.
const NOT_OWNED: u32 = u32::MAX;

/// The storage places of every evaluated element's entries (module docs).
#[derive(Debug, Clone, Default)]
pub(super) struct TangentSlots {
    layout: CsrLayout,
    /// Per evaluated element, the owned position of each node (`NOT_OWNED` for another
    /// rank's node).
    node_rows: Vec<[u32; 8]>,
    /// Per evaluated element and node pair `8·a + b`: the offset of node b's first column in
    /// the rows of node a, with [`OFF`] set when it is in the off-diagonal block.
    pairs: Vec<[u32; 64]>,
}

impl TangentSlots {
    /// The places of the elements of `disc` in the storage `layout` of the assembled pattern.
    /// Fails naming the first node pair the pattern does not hold as a whole 3 × 3 block.
    pub(super) fn new(layout: CsrLayout, disc: &Discretization) -> Result<TangentSlots, String> {
        let mut node_rows = Vec::with_capacity(disc.elements.len());
        let mut pairs = Vec::with_capacity(disc.elements.len());
        for loc in &disc.element_local {
            let dofs: [i32; 8] = std::array::from_fn(|a| disc.local_dofs[3 * loc[a] as usize]);
            let rows: [u32; 8] = std::array::from_fn(|a| match disc.owns_dof(dofs[a]) {
                true => ((dofs[a] as usize - disc.dof_lo) / 3) as u32,
                false => NOT_OWNED,
            });
            let mut p = [NOT_OWNED; 64];
            for a in (0..8).filter(|&a| rows[a] != NOT_OWNED) {
                for b in 0..8 {
                    p[8 * a + b] = node_block(&layout, disc, 3 * rows[a] as usize, dofs[b])?;
                }
            }
            node_rows.push(rows);
            pairs.push(p);
        }
        Ok(TangentSlots {
            layout,
            node_rows,
            pairs,
        })
    }

    /// Adds the owned rows of element `i`'s matrix `ke` to the values of the diagonal and
    /// off-diagonal blocks.
    pub(super) fn add(&self, i: usize, ke: &Matrix24, diag: &mut [f64], off: &mut [f64]) {
        let (rows, pairs) = (&self.node_rows[i], &self.pairs[i]);
        for a in (0..8).filter(|&a| rows[a] != NOT_OWNED) {
            for r in 0..3 {
                let row = 3 * rows[a] as usize + r;
                for b in 0..8 {
                    let s = pairs[8 * a + b];
                    let (values, start) = match s & OFF {
                        0 => (&mut *diag, self.layout.diag.rows[row]),
                        _ => (&mut *off, self.layout.off.rows[row]),
                    };
                    let base = start as usize + (s & !OFF) as usize;
                    for c in 0..3 {
                        values[base + c] += ke[(3 * a + r, 3 * b + c)];
                    }
                }
            }
        }
    }
}

/// The offset of the columns `col..col + 3` (a node's DOFs) in the owned rows `row..row + 3`,
/// flagged with [`OFF`] in the off-diagonal block; an error unless all nine entries are
/// there at the same offset.
fn node_block(layout: &CsrLayout, disc: &Discretization, row: usize, col: i32) -> Result<u32, String> {
    let (part, flag) = match disc.owns_dof(col) {
        true => (&layout.diag, 0),
        false => (&layout.off, OFF),
    };
    let at = |r: usize| -> Option<usize> {
        let (lo, hi) = (part.rows[r] as usize, part.rows[r + 1] as usize);
        let k = part.cols[lo..hi].binary_search(&col).ok()?;
        (hi - lo >= k + 3 && part.cols[lo + k + 1] == col + 1 && part.cols[lo + k + 2] == col + 2)
            .then_some(k)
    };
    let k = at(row);
    match k {
        Some(k) if at(row + 1) == Some(k) && at(row + 2) == Some(k) && k < OFF as usize => {
            Ok(k as u32 | flag)
        }
        _ => Err(format!(
            "the tangent's pattern does not hold the 3 x 3 block of rows {}-{} and columns {col}-{}",
            disc.dof_lo + row,
            disc.dof_lo + row + 2,
            col + 2
        )),
    }
}
