//! Prints AUTO's features and the rule it picks for each problem file given (`cargo run -p
//! fc3d-core --release --example auto_features -- FILES`).
use fc3d_core::{io::read_problem_file, ProblemFeatures};

fn main() {
    println!("problem nc density mu_min mu_max frictionless dominance asym spread singular");
    for a in std::env::args().skip(1) {
        let Ok(p) = read_problem_file(std::path::Path::new(&a)) else {
            continue;
        };
        let f = ProblemFeatures::of(&p);
        println!(
            "{} {} {:.3} {} {} {} {:.3e} {:.1e} {:.2e} {}",
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
            f.singular_contacts
        );
    }
}
