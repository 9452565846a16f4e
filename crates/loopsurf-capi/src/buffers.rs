//! Arrays handed to the caller: `malloc` blocks (so C's `free` releases
//! them too), made all or none.

use crate::status::{Fail, LS_ERR_INTERNAL};
use std::ffi::c_void;

/// Copies `data` into a fresh `malloc` block (never NULL on success).
pub(crate) unsafe fn malloc_copy<T: Copy>(data: &[T]) -> Result<*mut T, Fail> {
    let bytes = std::mem::size_of_val(data).max(1);
    let p = libc::malloc(bytes) as *mut T;
    if p.is_null() {
        return Err(Fail::new(
            LS_ERR_INTERNAL,
            format!("out of memory ({bytes} bytes)"),
        ));
    }
    std::ptr::copy_nonoverlapping(data.as_ptr(), p, data.len());
    Ok(p)
}

/// `malloc` blocks under construction: freed again on drop unless handed
/// over, so a function that fails half-way leaks nothing.
#[derive(Default)]
pub(crate) struct Blocks(Vec<*mut c_void>);

impl Blocks {
    pub(crate) unsafe fn copy<T: Copy>(&mut self, data: &[T]) -> Result<*mut T, Fail> {
        let p = malloc_copy(data)?;
        self.0.push(p as *mut c_void);
        Ok(p)
    }

    /// The caller now owns every block.
    pub(crate) fn hand_over(mut self) {
        self.0.clear();
    }
}

impl Drop for Blocks {
    fn drop(&mut self) {
        for &p in &self.0 {
            unsafe { libc::free(p) };
        }
    }
}
