// Links libgraspkit_c: from $GRASPKIT_LIB_DIR (an install's lib/), else from the project's own
// build folder (../../../build/lib from this crate). The folder is also the programs' run path,
// so tests and examples run without LD_LIBRARY_PATH.
use std::env;
use std::path::PathBuf;

fn main() {
    println!("cargo:rerun-if-env-changed=GRASPKIT_LIB_DIR");
    let dir = match env::var_os("GRASPKIT_LIB_DIR") {
        Some(dir) => PathBuf::from(dir),
        None => {
            let manifest = PathBuf::from(env::var_os("CARGO_MANIFEST_DIR").unwrap());
            manifest.join("../../../build/lib")
        }
    };
    if !dir.join("libgraspkit_c.so").exists() {
        println!(
            "cargo:warning=libgraspkit_c.so not found in {}: set GRASPKIT_LIB_DIR",
            dir.display()
        );
    }
    println!("cargo:rustc-link-search=native={}", dir.display());
    println!("cargo:rustc-link-lib=dylib=graspkit_c");
    println!("cargo:rustc-link-arg=-Wl,-rpath,{}", dir.display());
    println!("cargo:lib_dir={}", dir.display());
}
