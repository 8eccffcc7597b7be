//! Compiles the C test sources against the checked-in headers (include/fc3d.h through the
//! Siconos-named compat headers, as a host would) into a static library the tests call.

fn main() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let sources = [
        "c/capi_checks.c",
        "c/nsgs_options.c",
        "c/matrix_hostile.c",
        "c/solver_entries.c",
        "c/fc2d_checks.c",
        "c/rolling_checks.c",
        "c/workspace_checks.c",
        "c/global_checks.c",
    ];
    let mut build = cc::Build::new();
    build
        .include(root.join("../capi/include/siconos-compat"))
        .include(root.join("../capi/include"))
        .flag_if_supported("-std=c99")
        .flag_if_supported("-Wall")
        .flag_if_supported("-Wextra")
        .flag_if_supported("-Werror")
        .opt_level(2);
    for s in sources {
        build.file(root.join(s));
        println!("cargo:rerun-if-changed={s}");
    }
    println!("cargo:rerun-if-changed=../capi/include");
    build.compile("fc3d_capi_checks");
}
