//! Gives the shared library a versioned SONAME on ELF platforms: `libfc3d.so.MAJOR` (or
//! `libfc3d_native.so.MAJOR` for the build without Siconos names), so that hosts record the ABI
//! version they were linked against (scripts/install.sh installs the matching file names).
//! With the feature `embedded` (fc3d-mpi, whose cdylib carries this crate) it gives none: Cargo
//! passes a dependency's cdylib link arguments to the dependent's cdylib too, and this SONAME
//! would win over `libfc3d_mpi.so.MAJOR`.

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    if std::env::var_os("CARGO_FEATURE_EMBEDDED").is_some() {
        return;
    }
    if os == "linux" || os == "freebsd" || os == "netbsd" || os == "openbsd" {
        let major = std::env::var("CARGO_PKG_VERSION_MAJOR").unwrap_or_else(|_| "0".into());
        let name = if std::env::var_os("CARGO_FEATURE_SICONOS_ABI").is_some() {
            "libfc3d"
        } else {
            "libfc3d_native"
        };
        println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,{name}.so.{major}");
    }
}
