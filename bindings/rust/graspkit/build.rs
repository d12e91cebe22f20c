// The folder graspkit-sys linked libgraspkit_c from becomes the run path of this crate's tests
// and examples (link arguments do not pass from one package to the next). A program of yours
// that depends on this crate finds the library through the system's paths, LD_LIBRARY_PATH, or
// a run path of its own.
fn main() {
    if let Some(dir) = std::env::var_os("DEP_GRASPKIT_C_LIB_DIR") {
        println!("cargo:rustc-link-arg=-Wl,-rpath,{}", dir.to_string_lossy());
    }
}
