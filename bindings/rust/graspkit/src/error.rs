//! The error every call can give: the C ABI's status and its message, with the place in the
//! user's input it names.

use std::ffi::CStr;
use std::fmt;

use graspkit_sys as sys;

/// What kind of failure a call had (the C ABI's `graspkit_status`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// A null handle or pointer, a wrong array length.
    InvalidArgument,
    /// An index that names nothing.
    OutOfRange,
    /// A name that names nothing.
    NotFound,
    /// Bad input: a missing or malformed file, NaN, an unknown planner...
    Input,
    /// A string did not fit (the crate retries with a larger buffer, so rarely seen).
    BufferTooSmall,
    /// A Lua script failed; the message is its traceback.
    Script,
    /// A bug, or out of memory.
    Internal,
}

impl Status {
    fn from_raw(status: sys::graspkit_status) -> Status {
        match status {
            sys::GRASPKIT_ERROR_INVALID_ARGUMENT => Status::InvalidArgument,
            sys::GRASPKIT_ERROR_OUT_OF_RANGE => Status::OutOfRange,
            sys::GRASPKIT_ERROR_NOT_FOUND => Status::NotFound,
            sys::GRASPKIT_ERROR_INPUT => Status::Input,
            sys::GRASPKIT_ERROR_BUFFER_TOO_SMALL => Status::BufferTooSmall,
            sys::GRASPKIT_ERROR_SCRIPT => Status::Script,
            _ => Status::Internal,
        }
    }
}

/// A failed call: its status, the whole message (`file:line: <element>: what`) and its parts.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Error {
    /// The kind of failure.
    pub status: Status,
    /// The whole message.
    pub message: String,
    /// The file the input came from ("" when none).
    pub file: String,
    /// The line in that file (0 when unknown).
    pub line: i32,
    /// The element (XML tag) at fault ("" when none).
    pub element: String,
}

/// What every call of this crate returns.
pub type Result<T> = std::result::Result<T, Error>;

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for Error {}

pub(crate) fn text(pointer: *const std::os::raw::c_char) -> String {
    if pointer.is_null() {
        return String::new();
    }
    unsafe { CStr::from_ptr(pointer) }
        .to_string_lossy()
        .into_owned()
}

/// Turns a status into a Result, reading this thread's last error on failure.
pub(crate) fn check(status: sys::graspkit_status) -> Result<()> {
    if status == sys::GRASPKIT_OK {
        return Ok(());
    }
    unsafe {
        Err(Error {
            status: Status::from_raw(status),
            message: text(sys::graspkit_last_error()),
            file: text(sys::graspkit_last_error_file()),
            line: sys::graspkit_last_error_line(),
            element: text(sys::graspkit_last_error_element()),
        })
    }
}

/// An error made on this side (a path or name that cannot go to C).
pub(crate) fn invalid(message: &str) -> Error {
    Error {
        status: Status::InvalidArgument,
        message: message.to_string(),
        file: String::new(),
        line: 0,
        element: String::new(),
    }
}

/// [`invalid`] for the crate's modules.
pub(crate) fn invalid_pub(message: &str) -> Error {
    invalid(message)
}
