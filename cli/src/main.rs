//! The `fc3d` command.
//!
//! * `fc3d` solves every built-in scene ([`fc3d_core::scenes::default_scenes`]) with AUTO (or the
//!   solver of `--solver`) and prints a table: problem, contacts, storage, solver, iterations,
//!   error, status, time; for AUTO, the stages it took under each row.
//! * `fc3d FILE.dat [MORE FILES OR DIRECTORIES]` solves Siconos `.dat` problem files instead; a
//!   directory stands for the `*.dat` files directly in it (sorted by name; files that hold a problem
//!   fc3d does not handle, e.g. a 2D one, are skipped with a note on stderr).
//! * `fc3d solve ...` is the same as `fc3d ...`.
//! * `fc3d bench [FILES]` measures the speed–accuracy trade of the solvers: CSV, summary,
//!   performance profiles and work–precision pictures (see the `bench` module).
//! * `fc3d plot CSV --x COL --y COL [--by COL] -o STEM` draws a benchmark CSV (see `plot_csv`).
//! * `fc3d convert IN OUT` rewrites a problem file as `.dat` or FCLIB `.hdf5`, by OUT's
//!   extension, without changing a bit (see the `convert` module).
//!
//! Defaults: AUTO (fc3d's solver that chooses), tolerance 1e-8 on the natural-map error, at most
//! 100000 iterations. `--solver` takes any solver by name or Siconos id as `fc3d bench` does
//! (`NSGS`, `500/552`, `PROX`, `590`...), `--local` the local solver of NSGS, `--budget` a time
//! budget per problem, `--option NAME=VALUE` Siconos' option slots by name. The tolerance is tighter than Siconos'
//! 1e-4 default so that the table shows how accurate the solvers can be; the sweep limit leaves the
//! slow-converging problems of the Siconos collection room without letting one run for minutes.
//! The error column is the one measured on the returned `(r, u)`, not the solver's own test.
//!
//! Exit status: 0 when every problem was read and solved (converged or not: the status column
//! says), 1 when an input could not be read or solved (a message names it, the others are still
//! solved), 2 on a command-line error.

use std::process::ExitCode;

use clap::{Parser, Subcommand};

mod bench;
mod convert;
mod inputs;
mod plain_csv;
mod plot_csv;
mod scene;
mod solve;
mod units;
use solve::SolveArgs;

/// Solves 3D frictional contact problems FC(W, q, mu) (Signorini + Coulomb, Delassus form).
///
/// Without FILES, solves the built-in scenes. A file name that is also a subcommand's name
/// (`solve`, `bench`, `convert`) must be written with a path, e.g. `./solve`.
#[derive(Parser, Debug)]
#[command(name = "fc3d", version, args_conflicts_with_subcommands = true)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    #[command(flatten)]
    solve: SolveArgs,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Solve the built-in scenes or the given .dat files (what `fc3d` does without a subcommand).
    Solve(SolveArgs),
    /// Benchmark solvers: CSV, summary, performance profiles, work–precision curves.
    Bench(bench::BenchArgs),
    /// Convert a problem file between Siconos .dat and FCLIB .hdf5 (by OUT's extension),
    /// losslessly. FCLIB needs fc3d built with the `fclib` feature.
    Convert(convert::ConvertArgs),
    /// Generate a pile scene (seeded, deterministic) and write it as a Siconos .dat file.
    Scene(scene::SceneArgs),
    /// Draw one column of a benchmark CSV against another, log–log, as SVG and PNG.
    Plot(plot_csv::PlotArgs),
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        // Prints help/version (exit 0) or the usage error (exit 2).
        Err(e) => e.exit(),
    };
    let args = match cli.command {
        Some(Command::Solve(args)) => args,
        Some(Command::Bench(args)) => return bench::run(&args),
        Some(Command::Convert(args)) => return convert::run(&args),
        Some(Command::Scene(args)) => return scene::run(&args),
        Some(Command::Plot(args)) => return plot_csv::run(&args),
        None => cli.solve,
    };
    solve::run_solve(&args)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::spec::parse_spec;
    use crate::inputs::read_problem;
    use crate::solve::config_of;
    use clap::CommandFactory;
    use fc3d_core::{LocalSolverKind, Method, Rescaling};
    use std::path::PathBuf;
    use std::time::Duration;

    #[test]
    fn scene_writes_the_generated_problem_bit_for_bit() {
        let dir = std::env::temp_dir().join(format!("fc3d-scene-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let out = dir.join("p.dat");
        let spec = fc3d_core::scenes::PileSpec {
            contacts: 50,
            piles: 2,
            seed: 3,
        };
        for (shape, made) in [
            (None, fc3d_core::scenes::sphere_piles(&spec).unwrap()),
            (Some("boxes"), fc3d_core::scenes::box_piles(&spec).unwrap()),
        ] {
            let cli = Cli::try_parse_from(
                [
                    "fc3d",
                    "scene",
                    "--contacts",
                    "50",
                    "--piles",
                    "2",
                    "--seed",
                    "3",
                ]
                .into_iter()
                .chain(shape.map(|s| ["--shape", s]).into_iter().flatten())
                .map(String::from)
                .chain(["-o".to_string(), out.display().to_string()]),
            )
            .unwrap();
            let Some(Command::Scene(args)) = cli.command else {
                panic!("expected the scene subcommand");
            };
            assert_eq!(scene::run(&args), ExitCode::SUCCESS);
            let read = read_problem(&out).unwrap();
            assert_eq!(read.w(), made.w(), "{shape:?}");
            assert_eq!(read.q(), made.q());
            assert_eq!(read.mu(), made.mu());
        }
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn cli_is_well_formed() {
        Cli::command().debug_assert();
    }

    #[test]
    fn defaults_and_flags() {
        let cli = Cli::try_parse_from(["fc3d"]).unwrap();
        assert!(cli.command.is_none());
        assert!(cli.solve.paths.is_empty());
        assert_eq!(cli.solve.tol, 1e-8);
        assert_eq!(cli.solve.max_iter, 100_000);
        assert_eq!(cli.solve.local, None);
        assert_eq!(cli.solve.solver, parse_spec("AUTO").unwrap());
        assert_eq!(cli.solve.budget, None);

        let cli = Cli::try_parse_from([
            "fc3d",
            "a.dat",
            "dir",
            "--tol",
            "1e-6",
            "--max-iter",
            "50",
            "--local",
            "552",
        ])
        .unwrap();
        assert_eq!(
            cli.solve.paths,
            vec![PathBuf::from("a.dat"), PathBuf::from("dir")]
        );
        assert_eq!(cli.solve.tol, 1e-6);
        assert_eq!(cli.solve.max_iter, 50);
        assert_eq!(cli.solve.local, Some(LocalSolverKind::ProjectionOnCone));

        let cli = Cli::try_parse_from(["fc3d", "solve", "x.dat", "--local", "557"]).unwrap();
        match cli.command {
            Some(Command::Solve(a)) => {
                assert_eq!(a.paths, vec![PathBuf::from("x.dat")]);
                assert_eq!(a.local, Some(LocalSolverKind::ProjectionOnCylinder));
            }
            _ => panic!("expected the solve subcommand"),
        }

        // `bench` is a subcommand; its flags do not leak into `fc3d` / `fc3d solve`.
        let cli = Cli::try_parse_from(["fc3d", "bench", "x.dat", "--reps", "1"]).unwrap();
        match cli.command {
            Some(Command::Bench(a)) => {
                assert_eq!(a.paths, vec![PathBuf::from("x.dat")]);
                assert_eq!(a.reps, 1);
            }
            _ => panic!("expected the bench subcommand"),
        }
        assert!(Cli::try_parse_from(["fc3d", "--reps", "1"]).is_err());
        assert!(Cli::try_parse_from(["fc3d", "solve", "--timeout", "1s"]).is_err());
        // `--budget` is both a solve flag (one budget) and a bench flag (a list).
        assert!(Cli::try_parse_from(["fc3d", "solve", "--budget", "1ms"]).is_ok());
        // A file named like the subcommand, written with a path, is still a file.
        let cli = Cli::try_parse_from(["fc3d", "./bench"]).unwrap();
        assert!(cli.command.is_none());
        assert_eq!(cli.solve.paths, vec![PathBuf::from("./bench")]);
    }

    #[test]
    fn convert_takes_two_files_and_the_info_flags() {
        let cli = Cli::try_parse_from(["fc3d", "convert", "a.dat", "b.hdf5"]).unwrap();
        match cli.command {
            Some(Command::Convert(a)) => {
                assert_eq!(a.input, PathBuf::from("a.dat"));
                assert_eq!(a.output, PathBuf::from("b.hdf5"));
                assert_eq!((a.title, a.description, a.math_info), (None, None, None));
            }
            _ => panic!("expected the convert subcommand"),
        }
        let cli = Cli::try_parse_from([
            "fc3d",
            "convert",
            "a.hdf5",
            "b.h5",
            "--title",
            "T",
            "--description",
            "D",
            "--math-info",
            "M",
        ])
        .unwrap();
        match cli.command {
            Some(Command::Convert(a)) => {
                assert_eq!(a.title.as_deref(), Some("T"));
                assert_eq!(a.description.as_deref(), Some("D"));
                assert_eq!(a.math_info.as_deref(), Some("M"));
            }
            _ => panic!("expected the convert subcommand"),
        }
        for bad in [
            vec!["fc3d", "convert"],
            vec!["fc3d", "convert", "a.dat"],
            vec!["fc3d", "convert", "a.dat", "b.dat", "c.dat"],
            vec!["fc3d", "convert", "a.dat", "b.dat", "--tol", "1e-3"],
        ] {
            assert!(Cli::try_parse_from(&bad).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn bad_flags_are_errors() {
        for bad in [
            vec!["fc3d", "--local", "500"],
            vec!["fc3d", "--local", "x"],
            vec!["fc3d", "--tol", "-1"],
            vec!["fc3d", "--tol", "nan"],
            vec!["fc3d", "--tol", "inf"],
            vec!["fc3d", "--max-iter", "-3"],
            vec!["fc3d", "--frobnicate"],
            vec!["fc3d", "--solver", "PSOR"],
            vec!["fc3d", "--budget", "soon"],
            vec!["fc3d", "--option", "SICONOS_IPARAM_MAX_ITER"],
            vec!["fc3d", "--option", "NO_SUCH_SLOT=1"],
            vec!["fc3d", "--option", "SICONOS_DPARAM_TOL=x"],
        ] {
            assert!(Cli::try_parse_from(&bad).is_err(), "{bad:?}");
        }
        // Parsed, but refused when the configuration is built.
        for bad in [
            vec!["fc3d", "--solver", "PROX", "--local", "552"],
            vec!["fc3d", "--option", "SICONOS_IPARAM_MAX_ITER=2.5"],
            vec!["fc3d", "--option", "SICONOS_FRICTION_3D_IPARAM_RESCALING=3"],
            vec!["fc3d", "--option", "SICONOS_DPARAM_TOL=-1"],
            vec![
                "fc3d",
                "--solver",
                "AUTO",
                "--option",
                "SICONOS_FRICTION_3D_NSGS_RELAXATION_VALUE=0.5",
            ],
        ] {
            let cli = Cli::try_parse_from(&bad).unwrap();
            assert!(config_of(&cli.solve).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn solver_budget_and_options_build_the_config() {
        let cli = Cli::try_parse_from(["fc3d"]).unwrap();
        let c = config_of(&cli.solve).unwrap();
        assert_eq!(c.siconos_id(), 590);
        assert_eq!(
            (c.tolerance, c.max_iter, c.time_budget),
            (1e-8, 100_000, None)
        );
        let cli = Cli::try_parse_from([
            "fc3d",
            "--solver",
            "nsgs",
            "--local",
            "552",
            "--budget",
            "10ms",
            "--option",
            "SICONOS_IPARAM_MAX_ITER=77",
            "--option",
            "siconos_dparam_tol=1e-5",
            "--option",
            "SICONOS_FRICTION_3D_IPARAM_RESCALING=1",
            "--option",
            "SICONOS_FRICTION_3D_NSGS_RELAXATION_VALUE=0.9",
        ])
        .unwrap();
        let c = config_of(&cli.solve).unwrap();
        assert_eq!(c.label(), "NSGS/552");
        assert_eq!((c.tolerance, c.max_iter), (1e-5, 77));
        assert_eq!(c.time_budget, Some(Duration::from_millis(10)));
        assert_eq!(c.rescaling, Rescaling::Scalar);
        let Method::Nsgs(o) = c.method else { panic!() };
        assert_eq!(o.relaxation, Some(0.9));
        let cli = Cli::try_parse_from([
            "fc3d",
            "--solver",
            "504",
            "--option",
            "FC3D_DPARAM_TIME_BUDGET=0.5",
        ])
        .unwrap();
        let c = config_of(&cli.solve).unwrap();
        assert_eq!(c.label(), "NSN-AC/GP");
        assert_eq!(c.time_budget, Some(Duration::from_millis(500)));
    }
}
