//! Strings across the C ABI: Rust strings in as NUL-terminated copies, C strings out through a
//! buffer that grows to the length the library reports.

use std::ffi::CString;
use std::os::raw::c_char;
use std::path::Path;

use graspkit_sys as sys;

use crate::error::{check, invalid, Result};

pub(crate) fn c_string(text: &str) -> Result<CString> {
    CString::new(text).map_err(|_| invalid(&format!("'{}' holds a NUL byte", text)))
}

pub(crate) fn c_path(path: &Path) -> Result<CString> {
    let text = path
        .to_str()
        .ok_or_else(|| invalid(&format!("{} is not valid UTF-8", path.display())))?;
    c_string(text)
}

/// Calls `fill(buffer, capacity, &mut length)`, once more with a buffer of the reported length
/// when the first was too small.
pub(crate) fn read_string<F>(mut fill: F) -> Result<String>
where
    F: FnMut(*mut c_char, usize, *mut usize) -> sys::graspkit_status,
{
    let mut buffer = vec![0u8; 256];
    let mut length = 0usize;
    let mut status = fill(
        buffer.as_mut_ptr() as *mut c_char,
        buffer.len(),
        &mut length,
    );
    if status == sys::GRASPKIT_ERROR_BUFFER_TOO_SMALL {
        buffer = vec![0u8; length + 1];
        status = fill(
            buffer.as_mut_ptr() as *mut c_char,
            buffer.len(),
            &mut length,
        );
    }
    check(status)?;
    buffer.truncate(length);
    Ok(String::from_utf8_lossy(&buffer).into_owned())
}

/// NUL-terminated copies of `items` and the pointer array C reads them through; both must live
/// as long as the pointers are used.
pub(crate) struct CStrings {
    _owned: Vec<CString>,
    pointers: Vec<*const c_char>,
}

impl CStrings {
    /// Folder paths, as the options structs of the C ABI take them.
    pub(crate) fn from_paths(paths: &[std::path::PathBuf]) -> Result<CStrings> {
        let texts: Vec<String> = paths
            .iter()
            .map(|p| p.to_string_lossy().into_owned())
            .collect();
        CStrings::new(&texts)
    }

    pub(crate) fn new<S: AsRef<str>>(items: &[S]) -> Result<CStrings> {
        let owned = items
            .iter()
            .map(|s| c_string(s.as_ref()))
            .collect::<Result<Vec<_>>>()?;
        let pointers = owned.iter().map(|s| s.as_ptr()).collect();
        Ok(CStrings {
            _owned: owned,
            pointers,
        })
    }
    pub(crate) fn as_ptr(&self) -> *const *const c_char {
        if self.pointers.is_empty() {
            std::ptr::null()
        } else {
            self.pointers.as_ptr()
        }
    }
    pub(crate) fn len(&self) -> usize {
        self.pointers.len()
    }
}
