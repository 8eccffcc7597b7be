//! The fill of the factorizing families in the `SolveReport`: exact on problems where it is
//! known, absent for the families that factorize nothing.

use fc3d_core::scenes::{box_piles, sphere_piles, PileSpec};
use fc3d_core::{
    solve, AdmmOptions, AutoOptions, Fill, FrictionProblem, Method, NsgsOptions, NsnFormulation,
    NsnOptions, ProxOptions, SolveReport, SolverConfig,
};

fn run(p: &FrictionProblem<'_>, method: Method) -> SolveReport {
    // The fill is that of the first factorization: a few iterations show it.
    let config = SolverConfig::new(method)
        .with_tolerance(1e-8)
        .with_max_iter(10);
    let mut r = vec![0.0; p.size()];
    let mut u = vec![0.0; p.size()];
    solve(p, &config, &mut r, &mut u).unwrap()
}

/// Six spheres each on the ground on its own (six piles of one contact): W is block diagonal,
/// each block `diag(1/m, 1/m + R^2/I, 1/m + R^2/I)`. The Newton matrix stores the 9 entries of
/// each block, ADMM's `W + rho I` the 3 nonzero ones; an LU of a block-diagonal matrix creates
/// no entry: factors as large as the matrix.
#[test]
fn isolated_contacts_factor_without_fill() {
    let p = sphere_piles(&PileSpec {
        contacts: 6,
        piles: 6,
        seed: 1,
    })
    .unwrap();
    let nsn = run(&p, NsnOptions::new(NsnFormulation::AlartCurnier).into());
    assert_eq!(
        nsn.fill,
        Some(Fill {
            matrix_nnz: 54,
            factor_nnz: 54
        })
    );
    let admm = run(&p, AdmmOptions::default().into());
    assert_eq!(
        admm.fill,
        Some(Fill {
            matrix_nnz: 18,
            factor_nnz: 18
        })
    );
    assert_eq!(admm.fill.unwrap().ratio(), 1.0);
    assert_eq!(run(&p, NsgsOptions::default().into()).fill, None);
}

/// On a box pile the factors fill in; PROX reports its inner Newton matrix's fill (the same
/// pattern as NSN's, first factorization of `J` for `W + shift I`), AUTO the largest of its
/// stages'.
#[test]
fn a_box_pile_reports_its_fill_in_every_factorizing_family() {
    let p = box_piles(&PileSpec {
        contacts: 120,
        piles: 1,
        seed: 3,
    })
    .unwrap();
    let nsn = run(&p, NsnOptions::new(NsnFormulation::AlartCurnier).into())
        .fill
        .unwrap();
    eprintln!("NSN: {nsn:?}, ratio {:.2}", nsn.ratio());
    assert_eq!(nsn.matrix_nnz, 15840);
    assert!(nsn.factor_nnz > nsn.matrix_nnz);
    let prox = run(&p, ProxOptions::default().into()).fill.unwrap();
    eprintln!("PROX: {prox:?}");
    assert_eq!(prox.matrix_nnz, nsn.matrix_nnz);
    let admm = run(&p, AdmmOptions::default().into()).fill.unwrap();
    eprintln!("ADMM: {admm:?}, ratio {:.2}", admm.ratio());
    assert!(admm.factor_nnz >= admm.matrix_nnz && admm.matrix_nnz <= nsn.matrix_nnz);
    let auto = run(&p, AutoOptions::default().into());
    eprintln!("AUTO: {:?} {:?}", auto.fill, auto.stages);
    assert!(auto.fill.is_some());
}
