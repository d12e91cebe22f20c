//! Lua scenarios, plugins and the log: the process-wide parts of graspkit.

use std::ffi::CStr;
use std::os::raw::{c_char, c_int, c_void};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use graspkit_sys as sys;

use crate::error::{check, Result};
use crate::strings::{c_path, read_string, CStrings};

/// How to run a scenario.
#[derive(Clone, Debug, Default)]
pub struct ScriptOptions {
    /// Model roots, readable by the script.
    pub roots: Vec<PathBuf>,
    /// `arg[1]`, `arg[2]`, ...
    pub args: Vec<String>,
    /// Stop the script after this many seconds (0: no limit).
    pub timeout_seconds: f64,
    /// Lift the sandbox.
    pub unsafe_: bool,
}

/// Runs a Lua scenario as `graspkit run` does; returns its `os.exit` status (0 when it ran to
/// its end). A script error is `Err` with status `Script` and the traceback as the message.
pub fn run_script<P: AsRef<Path>>(path: P, options: &ScriptOptions) -> Result<i32> {
    let path = c_path(path.as_ref())?;
    let roots = CStrings::from_paths(&options.roots)?;
    let args = CStrings::new(&options.args)?;
    let raw = sys::graspkit_script_options {
        roots: roots.as_ptr(),
        root_count: roots.len(),
        args: args.as_ptr(),
        arg_count: args.len(),
        timeout_seconds: options.timeout_seconds,
        unsafe_: options.unsafe_ as c_int,
    };
    let mut status: c_int = 0;
    check(unsafe { sys::graspkit_run_script(path.as_ptr(), &raw, &mut status) })?;
    Ok(status)
}

/// A plugin found on the search path.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PluginInfo {
    /// Its name ("" when unreadable).
    pub name: String,
    /// Whether it loaded.
    pub loaded: bool,
    /// Why not, when it did not.
    pub error: String,
}

/// Lists every plugin on the search path as the probe's child process found it (none is loaded
/// into this process), loadable or not.
pub fn plugins_scan() -> Result<Vec<PluginInfo>> {
    let mut count = 0usize;
    check(unsafe { sys::graspkit_plugins_scan(&mut count) })?;
    let mut list = Vec::with_capacity(count);
    for i in 0..count {
        let mut name = vec![0u8; 256];
        let mut error = vec![0u8; 4096];
        let mut loaded: c_int = 0;
        check(unsafe {
            sys::graspkit_plugin_info(
                i,
                name.as_mut_ptr() as *mut c_char,
                name.len(),
                &mut loaded,
                error.as_mut_ptr() as *mut c_char,
                error.len(),
            )
        })?;
        let text = |b: &[u8]| {
            unsafe { CStr::from_ptr(b.as_ptr() as *const c_char) }
                .to_string_lossy()
                .into_owned()
        };
        list.push(PluginInfo {
            name: text(&name),
            loaded: loaded != 0,
            error: text(&error),
        });
    }
    Ok(list)
}

/// Loads one plugin file.
pub fn plugin_load<P: AsRef<Path>>(path: P) -> Result<()> {
    let path = c_path(path.as_ref())?;
    check(unsafe { sys::graspkit_plugin_load(path.as_ptr()) })
}

/// The folders searched for plugins, colon-separated.
pub fn plugin_search_path() -> Result<String> {
    read_string(|b, c, l| unsafe { sys::graspkit_plugin_search_path(b, c, l) })
}

/// One warning of the engine's (suspicious input that still loads).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LogRecord {
    /// What it is about: "unknown-element", "geometry", "mass", "robot", "eigengrasp",
    /// "virtual-contact", "plugin", "collision" or "script".
    pub kind: String,
    /// The file ("" when unknown).
    pub file: String,
    /// The line (0 when unknown).
    pub line: i32,
    /// The element ("" when none).
    pub element: String,
    /// What is wrong.
    pub message: String,
}

type LogCallback = Box<dyn Fn(&LogRecord) + Send + Sync>;

// The installed callback: one per process, as the engine has one warning handler.
static LOG_CALLBACK: Mutex<Option<LogCallback>> = Mutex::new(None);

unsafe extern "C" fn log_trampoline(
    _level: sys::graspkit_log_level,
    kind: *const c_char,
    file: *const c_char,
    line: c_int,
    element: *const c_char,
    message: *const c_char,
    _user: *mut c_void,
) {
    let record = LogRecord {
        kind: crate::error::text(kind),
        file: crate::error::text(file),
        line,
        element: crate::error::text(element),
        message: crate::error::text(message),
    };
    // Never unwind into C: a panicking callback is caught here.
    let _ = std::panic::catch_unwind(|| {
        if let Ok(guard) = LOG_CALLBACK.lock() {
            if let Some(callback) = guard.as_ref() {
                callback(&record);
            }
        }
    });
}

/// Sends every engine warning to `callback` (from the thread that caused it), or, with None,
/// back to the default (stderr). The library never writes to stdout.
pub fn set_log_callback(callback: Option<LogCallback>) -> Result<()> {
    let install = callback.is_some();
    *LOG_CALLBACK.lock().unwrap_or_else(|e| e.into_inner()) = callback;
    let f: sys::graspkit_log_fn = if install { Some(log_trampoline) } else { None };
    check(unsafe { sys::graspkit_set_log_callback(f, std::ptr::null_mut()) })
}
