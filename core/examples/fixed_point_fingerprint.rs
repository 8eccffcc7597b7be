//! Bitwise fingerprint of the optimization-based fixed points with Siconos' inner solvers (TFP
//! and PFP with 500, 566, 567; ACLMFP with its Gauss-Seidel): iterations, status, error and a
//! hash of the reactions on every shared `.dat` problem up to 6000 unknowns. Run it before and
//! after a refactoring of these families and diff the outputs: they must be identical.
//!
//! `cargo run --release -p fc3d-core --example fixed_point_fingerprint [FILE-SUBSTRING [METHOD-SUBSTRING]]`
use fc3d_core::io::dat::read_dat_file;
use fc3d_core::*;

fn main() {
    // Optional filters: a substring of the file name, then of the method's name.
    let args: Vec<String> = std::env::args().skip(1).collect();
    let file_filter = args.first().cloned().unwrap_or_default();
    let method_filter = args.get(1).cloned().unwrap_or_default();
    let dir = std::path::Path::new("../shared/data/siconos");
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "dat"))
        .collect();
    files.sort();
    let inners = [
        TrescaInnerSolver::GaussSeidel,
        TrescaInnerSolver::FixedPointViUpk,
        TrescaInnerSolver::ProjectedGradient,
    ];
    for f in files {
        if !f.to_string_lossy().contains(&file_filter) {
            continue;
        }
        let Ok(p) = read_dat_file(&f) else { continue };
        if p.size() > 6000 {
            continue;
        }
        let mut methods: Vec<(String, Method)> = Vec::new();
        for inner in inners {
            let tfp = TrescaOptions {
                inner,
                inner_max_iter: 200,
                ..Default::default()
            };
            methods.push((format!("TFP/{inner:?}"), Method::Tresca(tfp)));
            let pfp = PfpOptions {
                tangent: inner,
                inner_max_iter: 200,
                ..Default::default()
            };
            methods.push((format!("PFP/{inner:?}"), Method::Pfp(pfp)));
        }
        let aclm = AclmOptions {
            inner_max_iter: 200,
            ..Default::default()
        };
        methods.push(("ACLMFP".to_string(), Method::Aclm(aclm)));
        for (name, method) in methods {
            if !name.contains(&method_filter) {
                continue;
            }
            let config = SolverConfig::new(method)
                .with_tolerance(1e-10)
                .with_max_iter(20);
            let (mut r, mut u) = (vec![0.0; p.size()], vec![0.0; p.size()]);
            let line = match solve(&p, &config, &mut r, &mut u) {
                Ok(rep) => {
                    let h: u64 = r.iter().fold(0u64, |a, v| a.rotate_left(5) ^ v.to_bits());
                    format!("{} {:?} {:e} {h:x}", rep.iterations, rep.status, rep.error)
                }
                Err(e) => format!("error {e}"),
            };
            println!("{} {name} {line}", f.file_name().unwrap().to_string_lossy());
        }
    }
}
