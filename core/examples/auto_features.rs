//! Prints AUTO's features and the rule it picks (without a budget, at 1e-4/1e-6/1e-8) for each
//! problem file given (`cargo run -p fc3d-core --release --example auto_features -- FILES`).
use fc3d_core::solvers::auto::choose;
use fc3d_core::{io::read_problem_file, ProblemFeatures};

fn main() {
    println!("problem nc density mu_min mu_max frictionless dominance asym spread singular rules");
    for a in std::env::args().skip(1) {
        let Ok(p) = read_problem_file(std::path::Path::new(&a)) else {
            continue;
        };
        let f = ProblemFeatures::of(&p);
        let rules: Vec<String> = [1e-4, 1e-6, 1e-8]
            .iter()
            .map(|&t| choose(&f, t, None).0.to_string())
            .collect();
        println!(
            "{} {} {:.3} {} {} {} {:.3e} {:.1e} {:.2e} {} {}",
            std::path::Path::new(&a)
                .file_name()
                .unwrap()
                .to_string_lossy(),
            f.n_contacts,
            f.block_density,
            f.mu_min,
            f.mu_max,
            f.frictionless,
            f.diagonal_dominance,
            f.block_asymmetry,
            f.diagonal_spread,
            f.singular_contacts,
            rules.join("/")
        );
    }
}
