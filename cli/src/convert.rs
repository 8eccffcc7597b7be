//! `fc3d convert IN OUT`: rewrites a problem file in the format OUT's extension names, `.dat`
//! (Siconos' text format) or `.hdf5` / `.h5` (FCLIB). IN is read as `fc3d solve` reads it:
//! `.hdf5` / `.h5` as FCLIB, anything else as `.dat`; a global problem (M, H, q, b, mu: the
//! global `.dat` format, or `/fclib_global`) stays global (`/fclib_global` in FCLIB, M and H as
//! stored in IN for `.dat`, triplets when IN had no storage to keep), or with `--reduce` is
//! written as its reduction FC(H^T M^-1 H, H^T M^-1 q + b, mu).
//!
//! The conversion is lossless: W (M, H) keeps its storage and every value its bits, in both
//! directions (`.dat` -> `.hdf5` -> `.dat` gives back the same text). FCLIB's info strings are taken from
//! IN when it is an FCLIB file, else the title is IN's file name; `--title`, `--description` and
//! `--math-info` replace them. FCLIB needs fc3d built with the `fclib` feature: without it,
//! converting from or to `.hdf5` fails with a message saying so.
//!
//! Exit status: 0 when OUT was written, 1 when IN could not be read or OUT written (a message
//! names the file; OUT is then left as it was), 2 on a command-line error.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use crate::inputs::AnyProblem;
use clap::Args;
use fc3d_core::io::dat::write_global_dat_file;
use fc3d_core::io::{
    has_fclib_extension, read_fclib_info, write_fclib_global_file, write_problem_file, FclibInfo,
};
use fc3d_core::problem::GlobalProblem;
use fc3d_core::{Fc3dError, FrictionProblem};

#[derive(Args, Debug, Clone, PartialEq)]
pub struct ConvertArgs {
    /// The problem to read: FCLIB (.hdf5, .h5) or Siconos .dat (any other name).
    #[arg(value_name = "IN")]
    pub input: PathBuf,
    /// The file to write, replaced if it exists; its extension chooses the format: .dat, or
    /// .hdf5 / .h5 for FCLIB.
    #[arg(value_name = "OUT")]
    pub output: PathBuf,
    /// FCLIB title (default: IN's, or IN's file name).
    #[arg(long, value_name = "TEXT")]
    pub title: Option<String>,
    /// FCLIB description (default: IN's, or "converted from IN by fc3d convert").
    #[arg(long, value_name = "TEXT")]
    pub description: Option<String>,
    /// FCLIB mathematical information (default: IN's, or none).
    #[arg(long, value_name = "TEXT")]
    pub math_info: Option<String>,
    /// Write a global problem's reduction (the local problem W = H^T M^-1 H, q = H^T M^-1 q + b)
    /// instead of the global problem.
    #[arg(long)]
    pub reduce: bool,
}

pub fn run(args: &ConvertArgs) -> ExitCode {
    match convert(args) {
        Ok((problem, info)) => {
            let what = match &problem {
                AnyProblem::Local(p) => format!(
                    "W {} {}x{}",
                    p.w().storage_name(),
                    p.w().nrows(),
                    p.w().ncols()
                ),
                AnyProblem::Global(p, _) => format!(
                    "global, M {}x{} ({} entries), H {}x{} ({} entries)",
                    p.m().nrows(),
                    p.m().ncols(),
                    p.m().nnz(),
                    p.h().nrows(),
                    p.h().ncols(),
                    p.h().nnz()
                ),
            };
            println!(
                "{} -> {}: {} contacts, {what}{}",
                args.input.display(),
                args.output.display(),
                problem.n_contacts(),
                match (&info.title, has_fclib_extension(&args.output)) {
                    (Some(title), true) => format!(", title \"{title}\""),
                    _ => String::new(),
                }
            );
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("fc3d convert: {e}");
            ExitCode::from(1)
        }
    }
}

/// Reads IN, writes OUT; returns the problem written and the info written.
fn convert(args: &ConvertArgs) -> Result<(AnyProblem, FclibInfo), Fc3dError> {
    check_output_name(&args.output)?;
    let problem = match crate::inputs::read_any_problem(&args.input, true)? {
        AnyProblem::Global(p, _) if args.reduce => AnyProblem::Local(reduction(&p)?),
        p => p,
    };
    let info = if has_fclib_extension(&args.output) {
        info_for(args)?
    } else {
        FclibInfo::default()
    };
    match &problem {
        AnyProblem::Local(p) => write_problem_file(p, &args.output, &info)?,
        AnyProblem::Global(p, _) if has_fclib_extension(&args.output) => {
            write_fclib_global_file(p, &args.output, &info)?
        }
        AnyProblem::Global(p, storage) => write_global_dat_file(p, storage, &args.output)?,
    }
    Ok((problem, info))
}

/// The local problem of a global one (M factored, W assembled block-sparse).
fn reduction(problem: &GlobalProblem<'_>) -> Result<FrictionProblem<'static>, Fc3dError> {
    let mut operator = problem.operator()?;
    problem.reduce(&mut operator)
}

/// OUT must name a format (checked before IN is read).
fn check_output_name(output: &Path) -> Result<(), Fc3dError> {
    let dat = output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("dat"));
    if dat || has_fclib_extension(output) {
        Ok(())
    } else {
        Err(Fc3dError::Unsupported(format!(
            "{}: the output's extension must be .dat (Siconos) or .hdf5 / .h5 (FCLIB)",
            output.display()
        )))
    }
}

/// The FCLIB info of OUT: IN's (when IN is an FCLIB file) or defaults, then the flags.
fn info_for(args: &ConvertArgs) -> Result<FclibInfo, Fc3dError> {
    let mut info = if has_fclib_extension(&args.input) {
        read_fclib_info(&args.input)?
    } else {
        let name = args
            .input
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| args.input.display().to_string());
        FclibInfo {
            title: Some(name.clone()),
            description: Some(format!("converted from {name} by fc3d convert")),
            math_info: None,
            number_of_degrees_of_freedom: None,
        }
    };
    for (field, flag) in [
        (&mut info.title, &args.title),
        (&mut info.description, &args.description),
        (&mut info.math_info, &args.math_info),
    ] {
        if flag.is_some() {
            field.clone_from(flag);
        }
    }
    Ok(info)
}
