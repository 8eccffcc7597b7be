//! `fc3d scene --contacts N [--piles P] [--seed S] [--shape boxes] [--global] -o OUT` (or
//! `fc3d scene contacts=N,piles=P,seed=S,shape=boxes ...`, the spec of a `gen:` input): generates
//! a pile scene ([`fc3d_core::scenes::sphere_piles`]: spheres in square pyramids on the ground, or
//! [`fc3d_core::scenes::box_piles`]: stepped pyramids of boxes with 4 contact points per face
//! contact, or [`fc3d_core::scenes::fcc_piles`]: boxes of spheres in a face-centred cubic
//! lattice; one time step of rigid-body dynamics, sparse-block W) and writes it as a Siconos `.dat` file (or FCLIB
//! `.hdf5` when fc3d is built with the `fclib` feature), by OUT's extension. With `--global` the
//! scene is written in the global form instead (M block diagonal, one 6x6 block a body, H the
//! contact Jacobians, b = 0: [`GeneratedScene::generate_global`]), M and H as sparse matrices
//! (Siconos' `NM_SPARSE`, what its mechanics kernel hands `gfc3d_driver`), FCLIB `/fclib_global`
//! for `.hdf5`. The same arguments give the same file, byte for byte.
//!
//! Any command that reads problems also takes the scene without a file:
//! `gen:contacts=N,piles=P,seed=S[,shape=boxes]` in place of a path (e.g. `fc3d bench
//! gen:contacts=10000,piles=2`; spheres unless `shape=boxes`).
//!
//! Exit status: 0 when OUT was written, 1 when it could not be, 2 on a command-line error.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::Args;
use fc3d_core::io::dat::{write_global_dat_file, GlobalStorage, MatrixStorage};
use fc3d_core::io::{has_fclib_extension, write_fclib_global_file, write_problem_file, FclibInfo};
use fc3d_core::scenes::{GeneratedScene, PileShape, PileSpec};

#[derive(Args, Debug, Clone, PartialEq)]
pub struct SceneArgs {
    /// The scene as one spec, `contacts=N[,piles=P][,seed=S][,shape=spheres|boxes|fcc]` (as after
    /// `gen:`), in place of the flags.
    #[arg(value_name = "SPEC", value_parser = parse_scene,
          conflicts_with_all = ["contacts", "piles", "seed", "shape"])]
    pub spec: Option<GeneratedScene>,
    /// Total number of contacts (split evenly between the piles).
    #[arg(long, value_name = "N", required_unless_present = "spec")]
    pub contacts: Option<usize>,
    /// Number of separate piles (they share no body: independent islands of W).
    #[arg(long, value_name = "P", default_value_t = 1)]
    pub piles: usize,
    /// Seed of the pseudo-random jitter, masses and velocities.
    #[arg(long, value_name = "S", default_value_t = 1)]
    pub seed: u64,
    /// What the piles are made of: spheres, boxes (4 contact points per face contact), or fcc
    /// (boxes of spheres in a regular face-centred cubic lattice).
    #[arg(long, value_name = "SHAPE", default_value = "spheres", value_parser = parse_shape)]
    pub shape: PileShape,
    /// Write the global form (M, H, q, b, mu: Siconos' GlobalFrictionContactProblem) instead of
    /// the local one.
    #[arg(long)]
    pub global: bool,
    /// The file to write (replaced if it exists): .dat, or .hdf5 / .h5 for FCLIB.
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,
}

fn parse_shape(s: &str) -> Result<PileShape, String> {
    PileShape::from_name(s).map_err(|e| e.to_string())
}

fn parse_scene(s: &str) -> Result<GeneratedScene, String> {
    GeneratedScene::parse(s).map_err(|e| e.to_string())
}

/// The scene the arguments name (the spec, else the flags).
fn scene_of(args: &SceneArgs) -> GeneratedScene {
    args.spec.unwrap_or(GeneratedScene {
        pile: PileSpec {
            contacts: args.contacts.unwrap_or(0),
            piles: args.piles,
            seed: args.seed,
        },
        shape: args.shape,
    })
}

/// The command line that makes the scene, for FCLIB's description.
fn description(scene: &GeneratedScene, global: bool) -> String {
    let spec = scene.pile;
    format!(
        "fc3d scene --contacts {} --piles {} --seed {}{}{}",
        spec.contacts,
        spec.piles,
        spec.seed,
        match scene.shape {
            PileShape::Spheres => "",
            PileShape::Boxes => " --shape boxes",
            PileShape::Fcc => " --shape fcc",
        },
        if global { " --global" } else { "" }
    )
}

pub fn run(args: &SceneArgs) -> ExitCode {
    let scene = scene_of(args);
    if args.global {
        return run_global(&scene, &args.output);
    }
    let spec = scene.pile;
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
        description: Some(description(&scene, false)),
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

/// `--global`: the scene in the global form, written as a global `.dat` (M and H sparse) or an
/// FCLIB `/fclib_global`.
fn run_global(scene: &GeneratedScene, output: &Path) -> ExitCode {
    let start = Instant::now();
    let problem = match scene.generate_global() {
        Ok(p) => p,
        Err(e) => {
            eprintln!("fc3d: {e}");
            return ExitCode::from(1);
        }
    };
    let generated = start.elapsed();
    let written = if has_fclib_extension(output) {
        let info = FclibInfo {
            title: Some(format!("{} (global)", scene.name())),
            description: Some(description(scene, true)),
            math_info: None,
            number_of_degrees_of_freedom: i32::try_from(problem.ndof()).ok(),
        };
        write_fclib_global_file(&problem, output, &info)
    } else {
        let storage = GlobalStorage {
            m: MatrixStorage::Sparse,
            h: MatrixStorage::Sparse,
        };
        write_global_dat_file(&problem, &storage, output)
    };
    if let Err(e) = written {
        eprintln!("fc3d: {e}");
        return ExitCode::from(1);
    }
    println!(
        "{}: global form, {} contacts in {} piles, {} unknowns, M {} and H {} stored entries, \
         generated in {:.2} s, written in {:.2} s",
        output.display(),
        problem.n_contacts(),
        scene.pile.piles,
        problem.ndof(),
        problem.m().nnz(),
        problem.h().nnz(),
        generated.as_secs_f64(),
        (start.elapsed() - generated).as_secs_f64()
    );
    ExitCode::SUCCESS
}
