//! The "ray of no solution" test of `solve` (status `Unbounded`) on problems whose parts differ
//! in scale: a converged result of one part must not be flagged because another part's W is
//! much larger.

use std::path::Path;

use fc3d_core::io::read_dat_file;
use fc3d_core::{
    natural_map_error, solve, BlockSparseMatrix, Decomposition, Delassus, FrictionProblem,
    NsgsOptions, SolveStatus, SolverConfig,
};

fn shared(name: &str) -> FrictionProblem<'static> {
    read_dat_file(Path::new(&format!(
        "{}/../../shared/data/siconos/{name}",
        env!("CARGO_MANIFEST_DIR")
    )))
    .unwrap()
}

/// The block-diagonal problem with `a` and `b` side by side (no coupling between them).
fn side_by_side(a: &FrictionProblem<'_>, b: &FrictionProblem<'_>) -> FrictionProblem<'static> {
    let (wa, wb) = (
        a.w().to_block_sparse().unwrap(),
        b.w().to_block_sparse().unwrap(),
    );
    let na = a.n_contacts();
    let n = na + b.n_contacts();
    let mut row_ptr = vec![0usize];
    let mut col_idx = Vec::new();
    let mut blocks: Vec<[f64; 9]> = Vec::new();
    for (w, offset) in [(&wa, 0), (&wb, na)] {
        for i in 0..w.n_block_rows() {
            for k in w.row_ptr()[i]..w.row_ptr()[i + 1] {
                col_idx.push(w.col_idx()[k] + offset);
                blocks.push(*w.block(k));
            }
            row_ptr.push(col_idx.len());
        }
    }
    let w = BlockSparseMatrix::new(n, n, row_ptr, col_idx, blocks).unwrap();
    let q: Vec<f64> = a.q().iter().chain(b.q()).copied().collect();
    let mu: Vec<f64> = a.mu().iter().chain(b.mu()).copied().collect();
    FrictionProblem::new(Delassus::SparseBlock(w), q, mu).unwrap()
}

fn largest_diagonal(p: &FrictionProblem<'_>) -> f64 {
    (0..p.n_contacts())
        .filter_map(|c| p.w().diagonal_block(c))
        .flat_map(|b| [b[0][0].abs(), b[1][1].abs(), b[2][2].abs()])
        .fold(0.0, f64::max)
}

/// Capsules (W's diagonal up to 7) and Confeti-ex03 (up to 2.8e-4) side by side, solved by NSGS
/// over islands to 1e-6: it stops at an error of 1.2e-7, a solution of both parts. Scaled by
/// the largest diagonal entry of the whole W, Confeti's large reaction looked like a ray of no
/// solution and the result was reported `Unbounded`.
#[test]
fn a_solution_of_parts_of_different_scales_is_not_flagged_unbounded() {
    let a = shared("Capsules-i100-889.dat");
    let b = shared("Confeti-ex03-Fc3D-SBM.dat");
    assert!(largest_diagonal(&a) > 1e4 * largest_diagonal(&b));
    let p = side_by_side(&a, &b);
    for decomposition in [Decomposition::Islands, Decomposition::Sequential] {
        let options = NsgsOptions {
            decomposition,
            ..NsgsOptions::default()
        };
        let config = SolverConfig::new(options).with_tolerance(1e-6);
        let n = p.size();
        let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
        let report = solve(&p, &config, &mut r, &mut u).unwrap();
        assert_eq!(
            report.status,
            SolveStatus::Converged,
            "{decomposition:?}: {report:?}"
        );
        let mut check = vec![0.0; n];
        let e = natural_map_error(&p, &r, &mut check);
        assert!(
            e <= 1e-6 && (e - report.error).abs() <= 1e-12,
            "{e:e} {report:?}"
        );
        // Each part is solved on its own too; its own relative error is larger than its share
        // of the global one, which is normalised by the whole ||r|| (Confeti's reactions).
        let split = a.size();
        let mut ua = vec![0.0; split];
        let mut ub = vec![0.0; n - split];
        let ea = natural_map_error(&a, &r[..split], &mut ua);
        let eb = natural_map_error(&b, &r[split..], &mut ub);
        assert!(ea <= 1e-4 && eb <= 1e-6, "{decomposition:?}: {ea:e} {eb:e}");
    }
}

/// A genuine ray of no solution (two contacts that cannot both stop penetrating: u_N1 + u_N2 =
/// -2 whatever r, W's diagonal 1) beside Capsules (diagonal up to 7): never reported solved,
/// and reported `Unbounded`, as it is alone (`hardening.rs`).
#[test]
fn a_ray_beside_another_part_is_still_detected() {
    for other in ["Capsules-i100-889.dat"] {
        let a = shared(other);
        let s = 1.0;
        #[rustfmt::skip]
    let singular = BlockSparseMatrix::new(
        2, 2, vec![0, 2, 4], vec![0, 1, 0, 1],
        vec![
            [s, 0.0, 0.0, 0.0, s, 0.0, 0.0, 0.0, s],
            [-s, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            [-s, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            [s, 0.0, 0.0, 0.0, s, 0.0, 0.0, 0.0, s],
        ],
    )
    .unwrap();
        let ray = FrictionProblem::new(
            Delassus::SparseBlock(singular),
            vec![-1.0, 0.0, 0.0, -1.0, 0.0, 0.0],
            vec![0.5, 0.5],
        )
        .unwrap();
        let p = side_by_side(&a, &ray);
        let mut unbounded = 0;
        for decomposition in [Decomposition::Islands, Decomposition::Sequential] {
            let options = NsgsOptions {
                decomposition,
                ..NsgsOptions::default()
            };
            let config = SolverConfig::new(options)
                .with_tolerance(1e-4)
                .with_max_iter(100_000);
            let n = p.size();
            let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
            let report = solve(&p, &config, &mut r, &mut u).unwrap();
            eprintln!("{other}, {decomposition:?}: {report:?}");
            assert_ne!(
                report.status,
                SolveStatus::Converged,
                "{decomposition:?}: {report:?}"
            );
            unbounded += usize::from(report.status == SolveStatus::Unbounded);
        }
        assert_eq!(unbounded, 2);
    }
}

/// Every family's preset on the Capsules + Confeti-ex03 problem (it has a solution): a result
/// whose error is at the tolerance is reported `Converged`, never `Unbounded`.
#[test]
fn no_family_reports_a_solution_of_parts_of_different_scales_unbounded() {
    let p = side_by_side(
        &shared("Capsules-i100-889.dat"),
        &shared("Confeti-ex03-Fc3D-SBM.dat"),
    );
    let mut converged = 0;
    for method in fc3d_core::Method::presets() {
        let config = SolverConfig::new(method)
            .with_tolerance(1e-6)
            .with_max_iter(5000)
            .with_time_budget(Some(std::time::Duration::from_millis(500)));
        let n = p.size();
        let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
        let report = solve(&p, &config, &mut r, &mut u).unwrap();
        eprintln!("{}: {:?} {:e}", config.label(), report.status, report.error);
        if report.error <= 1e-6 {
            assert_eq!(report.status, SolveStatus::Converged, "{}", config.label());
            converged += 1;
        }
    }
    assert!(converged > 0);
}
