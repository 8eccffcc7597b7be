//! A fingerprint of ADMM (4 option sets, 3000 iterations, tolerance 1e-8) on every shared 3D problem: one line a run with its
//! iterations, status, error and a hash of the reaction's bits. Two builds that print the same
//! lines run the same iterates bit for bit (the check behind refactorings of these solvers):
//!
//! `cargo run --release -p fc3d-core --example admm_fingerprint > before.txt` (and after, then `diff`)

use fc3d_core::io::dat::read_dat_file;
use fc3d_core::*;
fn main() {
    let dir = std::path::Path::new("../shared/data/siconos");
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "dat"))
        .collect();
    files.sort();
    for f in files {
        let Ok(p) = read_dat_file(&f) else { continue };
        if p.size() > 3000 {
            continue;
        }
        for (k, opts) in [
            AdmmOptions::default(),
            AdmmOptions {
                rho_strategy: AdmmRhoStrategy::ResidualBalancing,
                ..Default::default()
            },
            AdmmOptions {
                rho_strategy: AdmmRhoStrategy::ScaledResidualBalancing,
                initial_rho: AdmmInitialRho::Eigenvalues,
                ..Default::default()
            },
            AdmmOptions {
                acceleration: AdmmAcceleration::None,
                initial_rho: AdmmInitialRho::NormInf,
                scalar_rescaling: true,
                ..Default::default()
            },
        ]
        .into_iter()
        .enumerate()
        {
            let config = SolverConfig::new(opts)
                .with_tolerance(1e-8)
                .with_max_iter(3000);
            let (mut r, mut u) = (vec![0.0; p.size()], vec![0.0; p.size()]);
            let rep = solve(&p, &config, &mut r, &mut u).unwrap();
            let h: u64 = r.iter().fold(0u64, |a, v| a.rotate_left(5) ^ v.to_bits());
            println!(
                "{} {k} {} {:?} {:e} {h:x}",
                f.file_name().unwrap().to_string_lossy(),
                rep.iterations,
                rep.status,
                rep.error
            );
        }
    }
}
