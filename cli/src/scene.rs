//! `fc3d scene --contacts N [--piles P] [--seed S] [--shape boxes] -o OUT`: generates a pile
//! scene ([`fc3d_core::scenes::sphere_piles`]: spheres in square pyramids on the ground, or
//! [`fc3d_core::scenes::box_piles`]: stepped pyramids of boxes with 4 contact points per face
//! contact; one time step of rigid-body dynamics, sparse-block W) and writes it as a Siconos `.dat` file (or FCLIB
//! `.hdf5` when fc3d is built with the `fclib` feature), by OUT's extension. The same arguments
//! give the same file, byte for byte.
//!
//! Any command that reads problems also takes the scene without a file:
//! `gen:contacts=N,piles=P,seed=S[,shape=boxes]` in place of a path (e.g. `fc3d bench
//! gen:contacts=10000,piles=2`; spheres unless `shape=boxes`).
//!
//! Exit status: 0 when OUT was written, 1 when it could not be, 2 on a command-line error.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use clap::Args;
use fc3d_core::io::{write_problem_file, FclibInfo};
use fc3d_core::scenes::{GeneratedScene, PileShape, PileSpec};

#[derive(Args, Debug, Clone, PartialEq)]
pub struct SceneArgs {
    /// Total number of contacts (split evenly between the piles).
    #[arg(long, value_name = "N")]
    pub contacts: usize,
    /// Number of separate piles (they share no body: independent islands of W).
    #[arg(long, value_name = "P", default_value_t = 1)]
    pub piles: usize,
    /// Seed of the pseudo-random jitter, masses and velocities.
    #[arg(long, value_name = "S", default_value_t = 1)]
    pub seed: u64,
    /// What the piles are made of: spheres, or boxes (4 contact points per face contact).
    #[arg(long, value_name = "SHAPE", default_value = "spheres", value_parser = parse_shape)]
    pub shape: PileShape,
    /// The file to write (replaced if it exists): .dat, or .hdf5 / .h5 for FCLIB.
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,
}

fn parse_shape(s: &str) -> Result<PileShape, String> {
    PileShape::from_name(s).map_err(|e| e.to_string())
}

pub fn run(args: &SceneArgs) -> ExitCode {
    let spec = PileSpec {
        contacts: args.contacts,
        piles: args.piles,
        seed: args.seed,
    };
    let scene = GeneratedScene {
        pile: spec,
        shape: args.shape,
    };
    let start = Instant::now();
    let problem = match scene.generate() {
        Ok(p) => p,
        Err(e) => {
            eprintln!("fc3d: {e}");
            return ExitCode::from(1);
        }
    };
    let generated = start.elapsed();
    let info = FclibInfo {
        title: Some(scene.name()),
        description: Some(format!(
            "fc3d scene --contacts {} --piles {} --seed {}{}",
            spec.contacts,
            spec.piles,
            spec.seed,
            if scene.shape == PileShape::Boxes {
                " --shape boxes"
            } else {
                ""
            }
        )),
        math_info: None,
        number_of_degrees_of_freedom: None,
    };
    if let Err(e) = write_problem_file(&problem, &args.output, &info) {
        eprintln!("fc3d: {e}");
        return ExitCode::from(1);
    }
    let blocks = match problem.w() {
        fc3d_core::Delassus::SparseBlock(w) => w.n_blocks(),
        _ => 0,
    };
    println!(
        "{}: {} contacts in {} piles, {} blocks of W ({:.1} per contact), generated in {:.2} s, \
         written in {:.2} s",
        args.output.display(),
        problem.n_contacts(),
        spec.piles,
        blocks,
        blocks as f64 / problem.n_contacts() as f64,
        generated.as_secs_f64(),
        (start.elapsed() - generated).as_secs_f64()
    );
    ExitCode::SUCCESS
}
