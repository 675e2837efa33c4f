//! [`CanonicalProduct`]: a matrix-vector product summed in the mesh's DOF order.

use super::error::{convert, to_petsc_int, to_usize, PetscError};
use super::gather::Gather;
use super::matrix::{MatRow, Matrix};
use super::vector::Vector;

/// The product y = A·x of a fixed matrix whose every row is summed in the mesh's DOF order, so
/// that y is the same bit for bit at any rank count. PETSc's `MatMult` sums a row's diagonal
/// block and then its off-diagonal block, an order that moves with the partition: the inertia
/// and damping forces of a dynamic stage (M·a, K₀·v) then differ in the last bits between 1
/// and 2 ranks, and the plasticity carries that further (10⁻³ of the displacement after the
/// coarse seed quake). The matrix's owned rows are copied at construction (later changes to
/// the matrix are not seen); x's entries in those rows' columns are gathered at every product.
pub struct CanonicalProduct {
    /// Start of each owned row in `position` and `value`, and one past the last.
    row_start: Vec<usize>,
    /// For every entry: its column's place among the gathered entries of x (a `u32` to halve
    /// the memory of the index; [`widen`] makes it an index again).
    position: Vec<u32>,
    /// For every entry, rows in order, each row's entries in the mesh's DOF order.
    value: Vec<f64>,
    gather: std::cell::RefCell<Gather>,
}

/// One entry of a row: its column's place in the mesh's DOF order, its PETSc column, its value.
type Entry = (u32, i32, f64);

impl CanonicalProduct {
    /// The product with `a` (assembled) for vectors laid out like `like`; `mesh_order[k]` is
    /// the PETSc index of the mesh's DOF k (`Discretization::canonical_dofs`).
    pub fn new(a: &Matrix, like: &Vector, mesh_order: &[i32]) -> Result<CanonicalProduct, PetscError> {
        let mut rank_in_mesh = vec![0u32; mesh_order.len()];
        for (k, &g) in mesh_order.iter().enumerate() {
            rank_in_mesh[to_usize(g, "DOF index")?] = convert(k, "mesh DOF")?;
        }
        let (lo, hi) = like.ownership_range()?;
        let mut rows: Vec<Vec<Entry>> = Vec::with_capacity(hi - lo);
        for r in lo..hi {
            let mut row = Self::row(a, r)?;
            for e in &mut row {
                e.0 = rank_in_mesh[to_usize(e.1, "column")?];
            }
            row.sort_unstable_by_key(|e| e.0);
            rows.push(row);
        }
        let mut columns: Vec<i32> = rows.iter().flatten().map(|e| e.1).collect();
        columns.sort_unstable();
        columns.dedup();
        let mut row_start = vec![0];
        let (mut position, mut value) = (Vec::new(), Vec::new());
        for row in &rows {
            for &(_, c, v) in row {
                position.push(convert(
                    columns.binary_search(&c).unwrap_or_default(),
                    "column place",
                )?);
                value.push(v);
            }
            row_start.push(value.len());
        }
        let gather = std::cell::RefCell::new(Gather::new(like, &columns)?);
        Ok(CanonicalProduct {
            row_start,
            position,
            value,
            gather,
        })
    }

    /// Row `r` of `a` as (0, column, value) entries.
    fn row(a: &Matrix, r: usize) -> Result<Vec<Entry>, PetscError> {
        let row = MatRow::get(a.raw, to_petsc_int(r, "row")?)?;
        let entries = row
            .cols()
            .iter()
            .zip(row.values())
            .map(|(&c, &v)| (0, c, v))
            .collect();
        row.restore()?;
        Ok(entries)
    }

    /// `y ← A x` (collective), every row summed in the mesh's DOF order.
    pub fn mult(&self, x: &Vector, y: &mut Vector) -> Result<(), PetscError> {
        let (starts, position, value) = (&self.row_start, &self.position, &self.value);
        let mut gather = self.gather.borrow_mut();
        let xs = gather.gather(x)?;
        xs.read(|xs| {
            y.write(|ys| {
                for (i, yi) in ys.iter_mut().enumerate() {
                    let entries = starts[i]..starts[i + 1];
                    *yi = entries.map(|k| value[k] * xs[widen(position[k])]).sum();
                }
            })
        })?
    }
}

/// A `u32` place as an index: lossless wherever a `usize` has at least 32 bits, which the
/// assertion below makes a condition of the build.
#[inline]
fn widen(i: u32) -> usize {
    const _: () = assert!(usize::BITS >= u32::BITS);
    usize::try_from(i).unwrap_or(usize::MAX)
}
