//! Builds the thin MPI shim and finds MPI through its compiler wrapper (`mpicc`, or the one named
//! by `FC3D_MPICC`): the wrapper's compile and link flags, and the C types of `MPI_Comm` and
//! `MPI_Fint` (a pointer in Open MPI, an `int` in MPICH), which a probe program compiled with the
//! wrapper prints as Rust types for `src/ffi.rs`.
//!
//! Without MPI the crate builds empty (a warning says so), so that `cargo test --workspace`
//! works on a machine without MPI; `FC3D_REQUIRE_MPI=1` (set by scripts/test-all.sh) turns
//! that into a build failure.

use std::path::PathBuf;
use std::process::Command;

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=shim/fc3d_mpi_shim.c");
    println!("cargo:rerun-if-env-changed=FC3D_MPICC");
    println!("cargo:rerun-if-env-changed=FC3D_REQUIRE_MPI");
    println!("cargo::rustc-check-cfg=cfg(fc3d_no_mpi)");
    let mpicc = std::env::var("FC3D_MPICC").unwrap_or_else(|_| "mpicc".into());
    let Some((compile, link)) = wrapper_flags(&mpicc) else {
        if std::env::var_os("FC3D_REQUIRE_MPI").is_some_and(|v| v != "0") {
            panic!("fc3d-mpi: no MPI compiler wrapper `{mpicc}` (apt-get install openmpi-bin libopenmpi-dev)");
        }
        println!("cargo:warning=fc3d-mpi: `{mpicc}` not found: libfc3d_mpi is built empty (apt-get install openmpi-bin libopenmpi-dev)");
        println!("cargo:rustc-cfg=fc3d_no_mpi");
        return;
    };
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("OUT_DIR"));
    probe_types(&mpicc, &out);

    let mut build = cc::Build::new();
    build.file("shim/fc3d_mpi_shim.c").warnings(true);
    for flag in &compile {
        if let Some(dir) = flag.strip_prefix("-I") {
            build.include(dir);
        } else {
            build.flag(flag);
        }
    }
    build.compile("fc3d_mpi_shim");

    for flag in &link {
        if let Some(dir) = flag.strip_prefix("-L") {
            println!("cargo:rustc-link-search=native={dir}");
        } else if let Some(lib) = flag.strip_prefix("-l") {
            println!("cargo:rustc-link-lib={lib}");
        } else if flag.starts_with("-Wl,") {
            println!("cargo:rustc-link-arg={flag}");
        }
    }
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    if os == "linux" || os == "freebsd" {
        let major = std::env::var("CARGO_PKG_VERSION_MAJOR").unwrap_or_else(|_| "0".into());
        println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,libfc3d_mpi.so.{major}");
    }
}

/// The wrapper's compile and link flags: Open MPI's `--showme:compile` / `--showme:link`, else
/// MPICH's `-compile_info` / `-link_info` (whose first word is the compiler).
fn wrapper_flags(mpicc: &str) -> Option<(Vec<String>, Vec<String>)> {
    let run = |arg: &str| -> Option<Vec<String>> {
        let out = Command::new(mpicc).arg(arg).output().ok()?;
        out.status.success().then(|| {
            String::from_utf8_lossy(&out.stdout)
                .split_whitespace()
                .map(str::to_owned)
                .collect()
        })
    };
    if let (Some(c), Some(l)) = (run("--showme:compile"), run("--showme:link")) {
        return Some((c, l));
    }
    let (mut c, mut l) = (run("-compile_info")?, run("-link_info")?);
    c.retain(|f| f.starts_with('-'));
    l.retain(|f| f.starts_with('-'));
    Some((c, l))
}

/// Writes `mpi_types.rs`: `MpiComm` and `MpiFint`, the Rust types with the ABI of `MPI_Comm` and
/// `MPI_Fint` in this MPI's `mpi.h`.
fn probe_types(mpicc: &str, out: &std::path::Path) {
    let src = out.join("probe.c");
    let exe = out.join("probe");
    std::fs::write(
        &src,
        r#"#include <mpi.h>
#include <stdio.h>
#define RUST_INT(x) _Generic((x), int: "std::os::raw::c_int", unsigned int: "std::os::raw::c_uint", \
    long: "std::os::raw::c_long", unsigned long: "std::os::raw::c_ulong", default: "")
int main(void) {
    const char *comm = RUST_INT((MPI_Comm)0);
    printf("/// The C type `MPI_Comm` of this MPI.\npub type MpiComm = %s;\n",
           comm[0] ? comm : "*mut std::ffi::c_void");
    printf("/// The C type `MPI_Fint` (a Fortran INTEGER) of this MPI.\npub type MpiFint = %s;\n",
           RUST_INT((MPI_Fint)0));
    return sizeof(MPI_Comm) <= sizeof(void *) ? 0 : 1;
}
"#,
    )
    .expect("write probe.c");
    let status = Command::new(mpicc)
        .arg(&src)
        .arg("-o")
        .arg(&exe)
        .status()
        .expect("run the MPI compiler wrapper");
    assert!(
        status.success(),
        "fc3d-mpi: {mpicc} could not build the type probe"
    );
    let output = Command::new(&exe).output().expect("run the type probe");
    assert!(
        output.status.success(),
        "fc3d-mpi: MPI_Comm is wider than a pointer in this MPI"
    );
    std::fs::write(out.join("mpi_types.rs"), output.stdout).expect("write mpi_types.rs");
}
