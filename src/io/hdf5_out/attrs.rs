//! Reading and writing HDF5 attributes.

use hdf5::types::VarLenUnicode;
use hdf5::{File, H5Type, Location};

use crate::io::error::IoError;

/// Reads a scalar attribute of the group or dataset at `object`.
pub(super) fn read_attr<T: H5Type>(file: &File, object: &str, name: &str) -> Result<T, IoError> {
    let context = || format!("reading attribute {name} of {object}");
    let attr = match file.group(object) {
        Ok(g) => g.attr(name),
        Err(_) => file.dataset(object).and_then(|d| d.attr(name)),
    };
    attr.and_then(|a| a.read_scalar::<T>())
        .map_err(|e| IoError::hdf5(context(), e))
}

pub(super) fn write_attr<T: H5Type>(location: &Location, name: &str, value: T) -> hdf5::Result<()> {
    location.new_attr::<T>().create(name)?.write_scalar(&value)
}

pub(super) fn write_attr_str(location: &Location, name: &str, value: &str) -> hdf5::Result<()> {
    let value: VarLenUnicode = value
        .parse()
        .map_err(|e| hdf5::Error::from(format!("attribute {name}: {e}")))?;
    location
        .new_attr::<VarLenUnicode>()
        .create(name)?
        .write_scalar(&value)
}
