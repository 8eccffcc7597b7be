//! The functions of Siconos 4.4's installed friction headers (local, rolling and global) against
//! what fc3d's compat headers declare and `libfc3d.so` exports (issues 12 and 26): names and prototypes come from the C compiler
//! (`gcc -aux-info`) at test time, the exclusions (with their reasons) from
//! docs/siconos-functions.md. Skipped when the Siconos headers or gcc are missing (the test
//! suite installs them).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::Command;

const SICONOS_INCLUDE: &str = "/usr/include/siconos/numerics";

/// The friction headers of issue 12; the compiler adds every header they include.
const FRICTION_HEADERS: &[&str] = &[
    "fc3d_Solvers.h",
    "FrictionContactProblem.h",
    "fc3d_compute_error.h",
    "NonSmoothDrivers.h",
    "SolverOptions.h",
    "SparseBlockMatrix.h",
    "RollingFrictionContactProblem.h",
    "rolling_fc_Solvers.h",
    "rolling_fc3d_compute_error.h",
    "rolling_fc2d_compute_error.h",
    // The global family (issue 26, ../shared/docs/siconos-global.md section 1).
    "GlobalFrictionContactProblem.h",
    "GlobalFrictionContactProblem_as_ConvexQP.h",
    "GlobalFrictionContactProblem_as_VI.h",
    "GlobalRollingFrictionContactProblem.h",
    "gfc3d_Solvers.h",
    "gfc3d_compute_error.h",
    "gfc3d_balancing.h",
    "gfc3d_nonsmooth_Newton_AlartCurnier.h",
    "gfc3d_Gams.h",
    "global_rolling_fc_Solvers.h",
    "fc3d_solvers_wr.h",
];

/// The matrix layer: of these headers only the functions Siconos' 3D friction tests call are
/// required (fc3d is not a matrix library).
const MATRIX_HEADERS: &[&str] = &[
    "NumericsMatrix.h",
    "SparseBlockMatrix.h",
    "CSparseMatrix.h",
    "NumericsSparseMatrix.h",
    "NM_MPI.h",
];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Siconos' sources, when scripts/siconos-suite.sh has extracted them.
fn siconos_sources() -> Option<PathBuf> {
    let p = root().join("target/siconos-src/siconos-4.4.0/numerics/src");
    p.join("FrictionContact/test").is_dir().then_some(p)
}

/// A declaration seen by the compiler: the header it is in and its prototype.
#[derive(Debug, Clone)]
struct Decl {
    header: String,
    prototype: String,
}

/// The non-static function declarations of a translation unit including `headers`, by name.
fn declarations(headers: &[String], includes: &[PathBuf]) -> BTreeMap<String, Decl> {
    let dir = std::env::temp_dir().join(format!("fc3d-siconos-functions-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let tag = includes.len() + headers.len();
    let src = dir.join(format!("unit{tag}.c"));
    let aux = dir.join(format!("unit{tag}.aux"));
    let text: String = headers
        .iter()
        .map(|h| format!("#include \"{h}\"\n"))
        .collect();
    std::fs::write(&src, text).unwrap();
    // `-aux-info` (the prototypes of a translation unit) is GCC's.
    let mut cc = Command::new("gcc");
    cc.arg("-fsyntax-only").arg("-aux-info").arg(&aux);
    for i in includes {
        cc.arg(format!("-I{}", i.display()));
    }
    let out = cc.arg(&src).output().expect("run cc");
    assert!(
        out.status.success(),
        "gcc failed on {headers:?}:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let aux_text = std::fs::read_to_string(&aux).unwrap();
    let mut decls = BTreeMap::new();
    // Lines read "/* <file>:<line>:<flags> */ <declaration>;".
    for line in aux_text.lines() {
        let Some(rest) = line.strip_prefix("/* ") else {
            continue;
        };
        let Some((location, decl)) = rest.split_once(" */ ") else {
            continue;
        };
        let file = location.split(':').next().unwrap_or("");
        let decl = decl.trim().trim_end_matches(';');
        if decl.starts_with("static ") {
            continue;
        }
        let Some(open) = decl.find(" (") else {
            continue;
        };
        let name = decl[..open]
            .rsplit(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
            .next()
            .unwrap_or("")
            .to_string();
        decls.insert(
            name,
            Decl {
                header: file.to_string(),
                prototype: normalize(decl),
            },
        );
    }
    decls
}

/// A prototype with the spellings that name the same C type made equal (`struct X` and the
/// typedef `X`, Siconos' `RawNumericsMatrix` alias) and without `extern`.
fn normalize(decl: &str) -> String {
    let decl = decl.trim_start_matches("extern ");
    let mut out = String::new();
    let mut rest = decl;
    // Drop the keyword `struct` (not an identifier ending in "struct").
    while let Some(k) = rest.find("struct ") {
        let keyword = rest[..k]
            .chars()
            .last()
            .is_none_or(|c| !(c.is_ascii_alphanumeric() || c == '_'));
        out.push_str(&rest[..k]);
        if !keyword {
            out.push_str("struct ");
        }
        rest = &rest[k + "struct ".len()..];
    }
    out.push_str(rest);
    out.replace("RawNumericsMatrix", "NumericsMatrix")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

/// The functions libfc3d.so exports. `cargo test` builds the crate as an rlib only, so the
/// shared library of this profile is (re)built here.
fn exported() -> Option<BTreeSet<String>> {
    // target/<profile>/deps/<this test> -> target/<profile>/libfc3d.so
    let exe = std::env::current_exe().ok()?;
    let profile_dir = exe.parent()?.parent()?;
    let mut build = Command::new(env!("CARGO"));
    build.args(["build", "-p", "fc3d", "--lib"]);
    // target/<profile>: "debug" is the dev profile, any other directory names its profile.
    let profile = profile_dir.file_name()?.to_str()?;
    if profile != "debug" {
        build.args(["--profile", profile]);
    }
    let status = build.current_dir(root()).status().ok()?;
    assert!(status.success(), "cargo build -p fc3d failed");
    let lib = profile_dir.join("libfc3d.so");
    if !lib.is_file() {
        return None;
    }
    let out = Command::new("nm")
        .args(["-D", "--defined-only"])
        .arg(&lib)
        .output()
        .ok()?;
    Some(
        String::from_utf8_lossy(&out.stdout)
            .lines()
            .filter_map(|l| {
                let mut w = l.split_whitespace();
                let (_, kind, name) = (w.next()?, w.next()?, w.next()?);
                (kind == "T").then(|| name.to_string())
            })
            .collect(),
    )
}

/// The identifiers of the sources Siconos' 3D friction tests are built from: the test programs
/// and collections of FrictionContact/test named in numerics_tests.cmake (not the 2D, global,
/// rolling or FCLIB ones) and the test utilities.
fn test_identifiers(src: &Path) -> BTreeSet<String> {
    let cmake = std::fs::read_to_string(src.join("../numerics_tests.cmake")).unwrap_or_default();
    let mut files: Vec<PathBuf> = std::fs::read_dir(src.join("FrictionContact/test"))
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            let name = p.file_name().unwrap().to_string_lossy().to_string();
            name.ends_with(".c")
                && cmake.contains(&name)
                && !["fc2d", "gfc3d", "rfc3d", "rolling", "fclib"]
                    .iter()
                    .any(|x| name.contains(x))
        })
        .collect();
    files.push(src.join("FrictionContact/test-utils/frictionContact_test_function.c"));
    files.push(src.join("FrictionContact/test-utils/frictionContact_test_utils.h"));
    files.push(src.join("tools/test-utils/test_utils.c"));
    files.push(src.join("tools/test-utils/test_utils.h"));
    let mut ids = BTreeSet::new();
    for f in files {
        let text = std::fs::read_to_string(&f).unwrap_or_default();
        for t in text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_')) {
            if !t.is_empty() {
                ids.insert(t.to_string());
            }
        }
    }
    ids
}

/// The exclusion table of docs/siconos-functions.md: (pattern, reason).
fn exclusions() -> Vec<(String, String)> {
    let doc = std::fs::read_to_string(root().join("docs/siconos-functions.md")).unwrap();
    doc.lines()
        .filter_map(|l| {
            let cells: Vec<&str> = l.split('|').map(str::trim).collect();
            // "| `pattern` | reason |" splits into ["", "`pattern`", "reason", ""].
            if cells.len() != 4 {
                return None;
            }
            let pattern = cells[1].strip_prefix('`')?.strip_suffix('`')?;
            Some((pattern.to_string(), cells[2].to_string()))
        })
        .collect()
}

/// `*` matches any run of characters.
fn matches(pattern: &str, name: &str) -> bool {
    let parts: Vec<&str> = pattern.split('*').collect();
    if parts.len() == 1 {
        return pattern == name;
    }
    let (first, last) = (parts[0], parts[parts.len() - 1]);
    if !name.starts_with(first) || !name.ends_with(last) || name.len() < first.len() + last.len() {
        return false;
    }
    let mut rest = &name[first.len()..name.len() - last.len()];
    for mid in &parts[1..parts.len() - 1] {
        match rest.find(mid) {
            Some(k) => rest = &rest[k + mid.len()..],
            None => return false,
        }
    }
    true
}

#[test]
fn siconos_friction_functions_are_declared_and_exported() {
    if !Path::new(SICONOS_INCLUDE).join("fc3d_Solvers.h").is_file()
        || Command::new("gcc").arg("--version").output().is_err()
    {
        eprintln!("Siconos headers or gcc missing: skipped");
        return;
    }
    let Some(exports) = exported() else {
        panic!("libfc3d.so not found next to the test's deps directory: build it (cargo build -p fc3d)");
    };
    let mut headers: Vec<String> = FRICTION_HEADERS.iter().map(|s| s.to_string()).collect();
    let mut siconos_includes = vec![
        PathBuf::from(SICONOS_INCLUDE),
        PathBuf::from("/usr/include/siconos"),
    ];
    let sources = siconos_sources();
    match &sources {
        Some(src) => {
            // Not installed by Debian; the friction tests include it.
            headers.push("AlartCurnierGenerated.h".into());
            siconos_includes.push(src.join("FrictionContact/Generated"));
        }
        None => eprintln!(
            "Siconos' sources not extracted (scripts/siconos-suite.sh does it): AlartCurnierGenerated.h and the matrix functions the tests call are not checked"
        ),
    }
    let siconos = declarations(&headers, &siconos_includes);
    let ours = declarations(
        &headers,
        &[
            root().join("capi/include/siconos-compat"),
            root().join("capi/include"),
        ],
    );
    let used = sources.as_deref().map(test_identifiers).unwrap_or_default();
    let is_matrix = |d: &Decl| {
        MATRIX_HEADERS
            .iter()
            .any(|h| d.header.ends_with(&format!("/{h}")))
    };
    let is_siconos = |d: &Decl| {
        d.header.starts_with(SICONOS_INCLUDE)
            || sources
                .as_ref()
                .is_some_and(|s| Path::new(&d.header).starts_with(s))
    };
    let required: BTreeMap<&String, &Decl> = siconos
        .iter()
        .filter(|(name, d)| is_siconos(d) && (!is_matrix(d) || used.contains(*name)))
        .collect();
    assert!(
        required.len() > 100,
        "only {} functions found: is the Siconos header set right?",
        required.len()
    );

    let table = exclusions();
    assert!(table.len() > 10, "the exclusion table was not read");
    let excluded = |name: &str| table.iter().find(|(p, _)| matches(p, name));
    let mut problems = Vec::new();
    for (pattern, reason) in &table {
        if !siconos.keys().any(|n| matches(pattern, n)) {
            problems.push(format!(
                "exclusion `{pattern}` matches no Siconos function: delete its row"
            ));
        }
        if reason.is_empty() {
            problems.push(format!("exclusion `{pattern}` gives no reason"));
        }
    }
    let mut provided = 0;
    for (name, d) in &required {
        let declared = ours.get(*name);
        if let Some((pattern, _)) = excluded(name) {
            if declared.is_some() || exports.contains(*name) {
                problems.push(format!(
                    "{name} is provided but excluded by `{pattern}`: delete or narrow that row"
                ));
            }
            continue;
        }
        match declared {
            None => problems.push(format!(
                "{name} ({}) is not declared by fc3d's headers",
                d.header
            )),
            Some(o) if o.prototype != d.prototype => problems.push(format!(
                "{name}: fc3d declares `{}`, Siconos `{}`",
                o.prototype, d.prototype
            )),
            Some(_) => {}
        }
        if !exports.contains(*name) {
            problems.push(format!("{name} is not exported by libfc3d.so"));
        }
        provided += 1;
    }
    eprintln!(
        "{} Siconos functions required, {provided} provided, {} excluded (docs/siconos-functions.md)",
        required.len(),
        required.len() - provided
    );
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn patterns_match_as_documented() {
    assert!(matches("fc3d_projection*", "fc3d_projectionOnCone_solve"));
    assert!(matches("fc3d_*_set_default", "fc3d_nsgs_set_default"));
    assert!(!matches("fc3d_*_set_default", "fc3d_nsgs"));
    assert!(matches("avi_driver", "avi_driver"));
    assert!(!matches("avi_driver", "avi_driver2"));
    assert!(!matches("a*a", "a"));
}
