//! The one place with raw HDF5 calls: collective transfer of a block of rows.

use std::ops::Range;
use std::ptr;

use hdf5::{Dataset, Datatype, H5Type};
use hdf5_sys::h5::hsize_t;
use hdf5_sys::h5d::{H5Dget_space, H5Dread, H5Dwrite};
use hdf5_sys::h5i::hid_t;
use hdf5_sys::h5p::{H5FD_mpio_xfer_t, H5Pclose, H5Pcreate, H5Pset_dxpl_mpio};
use hdf5_sys::h5s::{H5S_seloper_t, H5Sclose, H5Screate_simple, H5Sselect_hyperslab, H5Sselect_none};

/// The bytes of a slice of plain numbers (the values as they are in memory).
pub(super) fn as_bytes<T: H5Type + Copy>(values: &[T]) -> &[u8] {
    // SAFETY: table values are plain numbers (no padding, any bit pattern readable as
    // bytes); the byte slice covers exactly the memory of `values` and borrows it.
    unsafe { std::slice::from_raw_parts(values.as_ptr().cast::<u8>(), std::mem::size_of_val(values)) }
}

/// The buffer of a transfer.
pub(super) enum Buffer<'a, T> {
    /// Values to write.
    Write(&'a [T]),
    /// Space to read into.
    Read(&'a mut [T]),
}

/// Closes an HDF5 id when dropped.
struct Id(hid_t, unsafe extern "C" fn(hid_t) -> hdf5_sys::h5::herr_t);
impl Drop for Id {
    fn drop(&mut self) {
        if self.0 >= 0 {
            // SAFETY: the id was returned by the matching create call and is closed once.
            unsafe {
                (self.1)(self.0);
            }
        }
    }
}

/// Writes or reads the rows `rows` (`ncomp` values each) of `ds` with a collective MPI-IO
/// transfer. Every rank of the file's communicator must call this, with an empty range if it
/// holds no rows. The buffer length must be `rows.len() * ncomp`.
pub(super) fn transfer_rows<T: H5Type>(
    ds: &Dataset,
    rows: Range<u64>,
    ncomp: usize,
    buffer: Buffer<'_, T>,
) -> Result<(), String> {
    let count = rows.end - rows.start;
    let len = match &buffer {
        Buffer::Write(b) => b.len(),
        Buffer::Read(b) => b.len(),
    };
    if len as u64 != count * ncomp as u64 {
        return Err(format!("buffer of {len} values for {count} rows × {ncomp}"));
    }
    let one_d = ds.ndim() == 1;
    if one_d != (ncomp == 1) {
        return Err(format!(
            "dataset rank {} does not fit {ncomp} components",
            ds.ndim()
        ));
    }
    let dtype = Datatype::from_type::<T>().map_err(|e| e.to_string())?;
    hdf5::sync::sync(|| {
        let start: [hsize_t; 2] = [rows.start, 0];
        let block: [hsize_t; 2] = [count, ncomp as hsize_t];
        let rank = if one_d { 1 } else { 2 };
        let fspace = file_rows(ds, &start, &block, count)?;
        let mspace = memory_rows(rank, &block, count)?;
        let dxpl = collective_transfer()?;
        // SAFETY: all ids were checked above and are closed by `Id`; the buffer holds exactly
        // `count * ncomp` values of the memory type `dtype` (checked above).
        let status = unsafe {
            match buffer {
                Buffer::Write(b) => {
                    H5Dwrite(ds.id(), dtype.id(), mspace.0, fspace.0, dxpl.0, b.as_ptr().cast())
                }
                Buffer::Read(b) => H5Dread(
                    ds.id(),
                    dtype.id(),
                    mspace.0,
                    fspace.0,
                    dxpl.0,
                    b.as_mut_ptr().cast(),
                ),
            }
        };
        if status < 0 {
            return Err("H5Dwrite/H5Dread failed".to_string());
        }
        Ok(())
    })
}

/// The file space of `ds` with the rows `block` from `start` selected (none when `count` is 0).
/// Call under [`hdf5::sync::sync`].
fn file_rows(ds: &Dataset, start: &[hsize_t; 2], block: &[hsize_t; 2], count: u64) -> Result<Id, String> {
    // SAFETY: the id is checked before use and closed by `Id`; `start` and `block` hold the two
    // dimensions that a selection of a dataset of rank 1 or 2 reads.
    unsafe {
        let fspace = Id(H5Dget_space(ds.id()), H5Sclose);
        if fspace.0 < 0 {
            return Err("H5Dget_space failed".to_string());
        }
        let status = if count == 0 {
            H5Sselect_none(fspace.0)
        } else {
            H5Sselect_hyperslab(
                fspace.0,
                H5S_seloper_t::H5S_SELECT_SET,
                start.as_ptr(),
                ptr::null(),
                block.as_ptr(),
                ptr::null(),
            )
        };
        if status < 0 {
            return Err("selecting the file rows failed".to_string());
        }
        Ok(fspace)
    }
}

/// The memory space of `rank` dimensions of the shape `block` (nothing selected when `count`
/// is 0). Call under [`hdf5::sync::sync`].
fn memory_rows(rank: i32, block: &[hsize_t; 2], count: u64) -> Result<Id, String> {
    // SAFETY: the id is checked before use and closed by `Id`; `block` holds at least `rank`
    // dimensions.
    unsafe {
        let mspace = Id(H5Screate_simple(rank, block.as_ptr(), ptr::null()), H5Sclose);
        if mspace.0 < 0 {
            return Err("H5Screate_simple failed".to_string());
        }
        if count == 0 && H5Sselect_none(mspace.0) < 0 {
            return Err("H5Sselect_none failed".to_string());
        }
        Ok(mspace)
    }
}

/// A dataset transfer property list for a collective MPI-IO transfer. Call under
/// [`hdf5::sync::sync`].
fn collective_transfer() -> Result<Id, String> {
    // SAFETY: the id is checked before use and closed by `Id`.
    unsafe {
        let dxpl = Id(H5Pcreate(*hdf5::globals::H5P_DATASET_XFER), H5Pclose);
        if dxpl.0 < 0 || H5Pset_dxpl_mpio(dxpl.0, H5FD_mpio_xfer_t::H5FD_MPIO_COLLECTIVE) < 0 {
            return Err("setting up the collective transfer failed".to_string());
        }
        Ok(dxpl)
    }
}
