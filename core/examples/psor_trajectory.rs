//! The true error (133) after every sweep of NSGS/562 with over-relaxation and freezing
//! (`cargo run --release -p fc3d-core --example psor_trajectory -- FILE TOL OMEGA K`).
use std::path::Path;

use fc3d_core::io::read_problem_file;
use fc3d_core::{solve_with_observer, ErrorEvaluation, LocalSolverKind, NsgsOptions, SolverConfig};

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let p = read_problem_file(Path::new(&a[0])).expect("problem");
    let tol: f64 = a[1].parse().unwrap();
    let omega: f64 = a[2].parse().unwrap();
    let k: usize = a[3].parse().unwrap();
    let o = NsgsOptions {
        error_evaluation: ErrorEvaluation::Full,
        relaxation: (omega != 1.0).then_some(omega),
        freezing: (k > 0).then_some(k),
        ..NsgsOptions::with_local(LocalSolverKind::Quartic)
    };
    let config = SolverConfig::new(o)
        .with_tolerance(tol)
        .with_max_iter(20000);
    let n = p.size();
    let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
    let mut line = Vec::new();
    solve_with_observer(&p, &config, &mut r, &mut u, &mut |e| {
        line.push(format!("{:.1e}", e.error));
        if line.len() == 10 {
            println!("{:>5}: {}", e.iteration, line.join(" "));
            line.clear();
        }
    })
    .unwrap();
    println!("{}", line.join(" "));
}
