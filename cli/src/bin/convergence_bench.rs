//! Convergence at scale (issue 27 item 7): the runs and the report behind
//! `scripts/convergence-bench.sh`, which calls this binary once per (scene, method) so that each
//! run's peak memory is its own, and adds Siconos' rows (bench/scale.c) to the same CSV.
//!
//! ```text
//! convergence_bench solve --scene contacts=10000,piles=4,seed=1,shape=spheres --method TFP
//!     [--tols 1e-4,1e-6] [--budget SECONDS] [--max-iter N]
//! convergence_bench settling --spheres N --per-side K --steps S --method AUTO [--tol 1e-4]
//!     [--budget SECONDS] [--steps-csv FILE] [--dat-dir DIR --dat-every K]
//! convergence_bench report --csv results.csv [--settling settling.csv]
//! ```
//!
//! `solve`: reads the scene (`--scene` a .dat file: the shape column is then the file's name) or
//! generates it (local form; the global form for a global method's name or id,
//! `GlobalMethod::preset`), then per tolerance, loosest first, one solve from r = 0 cut by the
//! budget; once a tolerance is not reached the tighter ones are not run. One CSV row a tolerance
//! ([`SOLVE_HEADER`]): CPU and wall seconds of the whole call (set-up included), iterations,
//! products with W (`SolveReport::products`; an NSGS sweep counts as one; `-` where the family does
//! not count them), the reported error and the error recomputed here on the returned r, the RSS
//! the process holds once the scene is generated and the peak the solve adds above it.
//!
//! `settling`: `pile_settling_in_bin`, every step solved to the tolerance through one
//! [`Workspace`] (warm start by contact id); per-step rows to `--steps-csv`, one summary row
//! ([`SETTLING_HEADER`]) on stdout. `--dat-dir` writes every K-th step's problem as a .dat file
//! (for Siconos' cold solves of the same problems). A global method (name or id, e.g.
//! `NSGS_HFORM` or 691) runs `pile_settling_in_bin_global`: each step's M, H, q, b solved by
//! `solve_global` from the reactions the same contact ids had at the end of the previous step
//! (zero for a new id), as the workspace warm-starts the local form; its error is the global
//! one (`global_error`). `--dat-dir` takes a local method.
//!
//! `report`: the markdown tables of a results CSV (fc3d's rows and Siconos'), with Siconos' best
//! id per scene and tolerance and the ratio of fc3d's best to it.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use fc3d_core::global::{solve_global, GlobalConfig, GlobalMethod};
use fc3d_core::io::dat::write_dat_file;
use fc3d_core::measure::{global_error, ContactLaw};
use fc3d_core::scenes::sequences::{
    pile_settling_in_bin, pile_settling_in_bin_global, GlobalStep, Step,
};
use fc3d_core::scenes::GeneratedScene;
use fc3d_core::{natural_map_error, solve, Method, SolveReport, SolverConfig, Workspace};

#[path = "../plain_csv.rs"]
mod plain_csv;
use plain_csv::Table;

const SOLVE_HEADER: &str =
    "shape,contacts,piles,seed,library,method,tolerance,status,cpu_s,wall_s,\
iterations,products,error,recomputed_error,generate_s,held_mb,solve_peak_mb,load";

const SETTLING_HEADER: &str = "spheres,per_side,steps,library,method,tolerance,solved_steps,\
median_contacts,max_contacts,median_step_s,max_step_s,median_iterations,max_iterations,\
not_converged,max_error,total_solve_s,total_s,load";

const STEP_HEADER: &str = "step,contacts,warm_contacts,status,cpu_s,wall_s,iterations,error";

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("solve") => run_solve(&args[1..]),
        Some("settling") => run_settling(&args[1..]),
        Some("report") => run_report(&args[1..]),
        Some("header") => {
            println!("{SOLVE_HEADER}");
            Ok(())
        }
        Some("settling-header") => {
            println!("{SETTLING_HEADER}");
            Ok(())
        }
        _ => Err(
            "usage: convergence_bench solve|settling|report|header|settling-header ... \
                  (see the source's documentation)"
                .to_string(),
        ),
    };
    if let Err(e) = result {
        eprintln!("convergence_bench: {e}");
        std::process::exit(2);
    }
}

/// `--key value` options.
fn options(args: &[String]) -> Result<BTreeMap<String, String>, String> {
    let mut map = BTreeMap::new();
    let mut it = args.iter();
    while let Some(key) = it.next() {
        let key = key
            .strip_prefix("--")
            .ok_or_else(|| format!("'{key}' is not an option"))?;
        let value = it.next().ok_or_else(|| format!("--{key} needs a value"))?;
        map.insert(key.to_string(), value.clone());
    }
    Ok(map)
}

fn parsed<T: std::str::FromStr>(
    opts: &BTreeMap<String, String>,
    key: &str,
    default: Option<T>,
) -> Result<T, String> {
    match opts.get(key) {
        Some(v) => v.parse().map_err(|_| format!("--{key}: cannot read '{v}'")),
        None => default.ok_or_else(|| format!("--{key} is required")),
    }
}

/// CPU time of the calling thread (the solvers run on it), in seconds, at nanosecond
/// resolution: the first field of /proc/thread-self/schedstat. On a shared machine it leaves
/// out the waits for a core that wall time adds at random (as bench/scale.c's process CPU time).
fn cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(f64::NAN, |ns| ns * 1e-9)
}

fn status_kb(key: &str) -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with(key))
                .and_then(|l| l.split_whitespace().nth(1)?.parse().ok())
        })
        .unwrap_or(f64::NAN)
}

/// Resets the peak RSS (VmHWM) to the current RSS, so that the next reading is the peak of what
/// follows.
fn reset_peak() {
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next().map(str::to_string))
        .unwrap_or_else(|| "?".into())
}

/// A method given by name or id: a local one, else a global one (run on the global form).
enum AnyMethod {
    Local(Method),
    Global(GlobalMethod),
}

fn method_named(name: &str) -> Result<AnyMethod, String> {
    if let Some(m) = Method::preset(name) {
        return Ok(AnyMethod::Local(m));
    }
    GlobalMethod::preset(name)
        .map(AnyMethod::Global)
        .ok_or_else(|| format!("unknown method '{name}' (a local or global name or id)"))
}

/// Products with W: the report's count, or the sweeps for NSGS (a sweep reads W once).
fn products(method: &Method, report: &SolveReport) -> String {
    match (report.products, method) {
        (Some(k), _) => k.to_string(),
        (None, Method::Nsgs(_)) => report.iterations.to_string(),
        _ => "-".into(),
    }
}

struct Outcome {
    status: String,
    converged: bool,
    iterations: usize,
    products: String,
    error: f64,
    recomputed: f64,
}

fn run_solve(args: &[String]) -> Result<(), String> {
    let opts = options(args)?;
    let spec: String = parsed(&opts, "scene", None)?;
    let name: String = parsed(&opts, "method", None)?;
    let method = method_named(&name)?;
    let mut tols: Vec<f64> = parsed::<String>(&opts, "tols", Some("1e-4,1e-6".into()))?
        .split(',')
        .map(|t| t.trim().parse().map_err(|_| format!("tolerance '{t}'")))
        .collect::<Result<_, _>>()?;
    tols.sort_by(|a, b| b.total_cmp(a));
    let budget = Duration::from_secs_f64(parsed(&opts, "budget", Some(30.0))?);
    let max_iter: usize = parsed(&opts, "max-iter", Some(1_000_000))?;

    let t = Instant::now();
    // A .dat file (a settling step written by `settling --dat-dir`), or a generated scene.
    let (local, global, scene_columns) = if spec.ends_with(".dat") {
        let AnyMethod::Local(_) = &method else {
            return Err("a .dat file is solved by local methods".into());
        };
        let p = fc3d_core::io::read_problem_file(std::path::Path::new(&spec))
            .map_err(|e| e.to_string())?;
        let stem = std::path::Path::new(&spec)
            .file_stem()
            .map_or(String::new(), |s| s.to_string_lossy().into_owned());
        let columns = format!("{stem},{},,", p.n_contacts());
        (Some(p), None, columns)
    } else {
        let scene = GeneratedScene::parse(&spec).map_err(|e| e.to_string())?;
        let columns = format!(
            "{},{},{},{}",
            scene.shape.label(),
            scene.pile.contacts,
            scene.pile.piles,
            scene.pile.seed
        );
        match &method {
            AnyMethod::Local(_) => (
                Some(scene.generate().map_err(|e| e.to_string())?),
                None,
                columns,
            ),
            AnyMethod::Global(_) => (
                None,
                Some(scene.generate_global().map_err(|e| e.to_string())?),
                columns,
            ),
        }
    };
    let generate_s = t.elapsed().as_secs_f64();
    let mut reached = true;
    for tol in tols {
        let prefix = format!("{scene_columns},fc3d,{name},{tol:e}");
        if !reached {
            println!(
                "{prefix},not-run,,,,,,,{generate_s:.3},,,{}",
                load_average()
            );
            continue;
        }
        let held_kb = status_kb("VmRSS:");
        reset_peak();
        let (cpu0, wall0) = (cpu_seconds(), Instant::now());
        let outcome = match (&method, &local, &global) {
            (AnyMethod::Local(m), Some(p), _) => {
                let config = SolverConfig::new(*m)
                    .with_tolerance(tol)
                    .with_max_iter(max_iter)
                    .with_time_budget(Some(budget));
                let (mut r, mut u) = (vec![0.0; p.size()], vec![0.0; p.size()]);
                let report = solve(p, &config, &mut r, &mut u).map_err(|e| e.to_string())?;
                let recomputed = natural_map_error(p, &r, &mut u);
                Outcome {
                    status: report.status.name().to_string(),
                    converged: report.converged(),
                    iterations: report.iterations,
                    products: products(m, &report),
                    error: report.error,
                    recomputed,
                }
            }
            (AnyMethod::Global(m), _, Some(p)) => {
                let mut config = GlobalConfig::new(*m);
                config.tolerance = tol;
                config.max_iter = max_iter;
                config.time_budget = Some(budget);
                let (mut r, mut u, mut v) = (
                    vec![0.0; p.size()],
                    vec![0.0; p.size()],
                    vec![0.0; p.ndof()],
                );
                let report =
                    solve_global(p, &config, &mut r, &mut u, &mut v).map_err(|e| e.to_string())?;
                // Siconos' global error (the measure the global solvers report), recomputed
                // here on the returned (r, v) and the problem's M and H.
                let recomputed = global_error(p, ContactLaw::Coulomb, &r, &mut u, &v);
                Outcome {
                    status: report.status.name().to_string(),
                    converged: report.converged(),
                    iterations: report.iterations,
                    products: "-".into(),
                    error: report.error,
                    recomputed,
                }
            }
            _ => unreachable!("the scene is generated in the method's form"),
        };
        let (cpu, wall) = (cpu_seconds() - cpu0, wall0.elapsed().as_secs_f64());
        let peak_kb = status_kb("VmHWM:");
        reached = outcome.converged;
        println!(
            "{prefix},{},{cpu:.4},{wall:.4},{},{},{:.3e},{:.3e},{generate_s:.3},{:.1},{:.1},{}",
            outcome.status,
            outcome.iterations,
            outcome.products,
            outcome.error,
            outcome.recomputed,
            held_kb / 1024.0,
            (peak_kb - held_kb).max(0.0) / 1024.0,
            load_average()
        );
    }
    Ok(())
}

fn median(v: &[f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    let n = s.len();
    if n % 2 == 1 {
        s[n / 2]
    } else {
        0.5 * (s[n / 2 - 1] + s[n / 2])
    }
}

/// What the settling run records of one step.
struct StepRow {
    index: usize,
    contacts: usize,
    warm: usize,
    status: &'static str,
    cpu: f64,
    wall: f64,
    iterations: usize,
    converged: bool,
    error: f64,
}

/// The local form: every step through one [`Workspace`] (warm start by contact id).
fn settle_local(
    (spheres, per_side, steps): (usize, usize, usize),
    config: &SolverConfig,
    dat: Option<(&std::path::Path, usize)>,
    record: &mut dyn FnMut(StepRow),
) -> Result<(), String> {
    let mut workspace = Workspace::new();
    let mut failure: Option<String> = None;
    let mut step_index = 0usize;
    let mut solver = |step: &Step| -> Vec<f64> {
        let p = &step.problem;
        let n = p.size();
        let (mut r, mut u) = (vec![0.0; n], vec![0.0; n]);
        if failure.is_some() {
            return r;
        }
        let warm = step
            .ids
            .iter()
            .filter(|id| workspace.last_reaction(**id).is_some())
            .count();
        let (cpu0, wall0) = (cpu_seconds(), Instant::now());
        match workspace.solve(p, config, &step.ids, &mut r, &mut u) {
            Ok(report) => {
                let (cpu, wall) = (cpu_seconds() - cpu0, wall0.elapsed().as_secs_f64());
                record(StepRow {
                    index: step_index,
                    contacts: p.n_contacts(),
                    warm,
                    status: report.status.name(),
                    cpu,
                    wall,
                    iterations: report.iterations,
                    converged: report.converged(),
                    error: report.error,
                });
                if let Some((dir, every)) = dat {
                    if every > 0 && step_index % every == every - 1 {
                        let path = dir.join(format!("settling-step{step_index:04}.dat"));
                        if let Err(e) = write_dat_file(p, &path) {
                            failure = Some(format!("{}: {e}", path.display()));
                        }
                    }
                }
            }
            Err(e) => failure = Some(e.to_string()),
        }
        step_index += 1;
        r
    };
    let _ = pile_settling_in_bin(spheres, per_side, steps, &mut solver);
    failure.map_or(Ok(()), Err)
}

/// The global form: every step's M, H, q, b solved from the reactions its contact ids had at
/// the end of the previous step (zero for a new id); the time includes the solve's set-up
/// (M factored, the method's data), as a host calling it every step would pay it.
fn settle_global(
    (spheres, per_side, steps): (usize, usize, usize),
    config: &GlobalConfig,
    record: &mut dyn FnMut(StepRow),
) -> Result<(), String> {
    let mut memory: std::collections::HashMap<i64, [f64; 3]> = std::collections::HashMap::new();
    let mut failure: Option<String> = None;
    let mut step_index = 0usize;
    let mut solver = |step: &GlobalStep| -> Vec<f64> {
        let p = &step.problem;
        let mut r = vec![0.0; p.size()];
        if failure.is_some() {
            return r;
        }
        let mut warm = 0;
        for (rc, id) in r.chunks_exact_mut(3).zip(&step.ids) {
            if let Some(m) = memory.get(id) {
                rc.copy_from_slice(m);
                warm += 1;
            }
        }
        let (mut u, mut v) = (vec![0.0; p.size()], vec![0.0; p.ndof()]);
        let (cpu0, wall0) = (cpu_seconds(), Instant::now());
        match solve_global(p, config, &mut r, &mut u, &mut v) {
            Ok(report) => {
                let (cpu, wall) = (cpu_seconds() - cpu0, wall0.elapsed().as_secs_f64());
                record(StepRow {
                    index: step_index,
                    contacts: p.n_contacts(),
                    warm,
                    status: report.status.name(),
                    cpu,
                    wall,
                    iterations: report.iterations,
                    converged: report.converged(),
                    error: report.error,
                });
                memory = step
                    .ids
                    .iter()
                    .zip(r.chunks_exact(3))
                    .map(|(&id, rc)| (id, [rc[0], rc[1], rc[2]]))
                    .collect();
            }
            Err(e) => {
                failure = Some(e.to_string());
                r.iter_mut().for_each(|x| *x = 0.0);
            }
        }
        step_index += 1;
        r
    };
    let _ = pile_settling_in_bin_global(spheres, per_side, steps, &mut solver);
    failure.map_or(Ok(()), Err)
}

fn run_settling(args: &[String]) -> Result<(), String> {
    let opts = options(args)?;
    let spheres: usize = parsed(&opts, "spheres", None)?;
    let per_side: usize = parsed(&opts, "per-side", None)?;
    let steps: usize = parsed(&opts, "steps", Some(200))?;
    let name: String = parsed(&opts, "method", Some("AUTO".into()))?;
    let method = method_named(&name)?;
    let tol: f64 = parsed(&opts, "tol", Some(1e-4))?;
    let budget = Duration::from_secs_f64(parsed(&opts, "budget", Some(30.0))?);
    let dat_dir = opts.get("dat-dir").map(PathBuf::from);
    if dat_dir.is_some() && matches!(method, AnyMethod::Global(_)) {
        return Err("--dat-dir writes local problems: it takes a local method".into());
    }
    let dat_every: usize = parsed(&opts, "dat-every", Some(20))?;
    let mut steps_csv = match opts.get("steps-csv") {
        Some(path) => {
            let mut f = std::fs::File::create(path).map_err(|e| format!("{path}: {e}"))?;
            use std::io::Write;
            writeln!(f, "{STEP_HEADER}").map_err(|e| e.to_string())?;
            Some(f)
        }
        None => None,
    };
    if let Some(dir) = &dat_dir {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    let mut rows: Vec<(usize, f64, usize, bool, f64)> = Vec::new();
    let total = Instant::now();
    let mut record = |row: StepRow| {
        if let Some(f) = steps_csv.as_mut() {
            use std::io::Write;
            let _ = writeln!(
                f,
                "{},{},{},{},{:.5},{:.5},{},{:.3e}",
                row.index,
                row.contacts,
                row.warm,
                row.status,
                row.cpu,
                row.wall,
                row.iterations,
                row.error
            );
        }
        rows.push((
            row.contacts,
            row.cpu,
            row.iterations,
            row.converged,
            row.error,
        ));
    };
    match method {
        AnyMethod::Local(m) => {
            let config = SolverConfig::new(m)
                .with_tolerance(tol)
                .with_max_iter(1_000_000)
                .with_time_budget(Some(budget));
            settle_local(
                (spheres, per_side, steps),
                &config,
                dat_dir.as_deref().map(|d| (d, dat_every)),
                &mut record,
            )?;
        }
        AnyMethod::Global(m) => {
            let mut config = GlobalConfig::new(m);
            config.tolerance = tol;
            config.max_iter = 1_000_000;
            config.time_budget = Some(budget);
            settle_global((spheres, per_side, steps), &config, &mut record)?;
        }
    }
    let times: Vec<f64> = rows.iter().map(|r| r.1).collect();
    let its: Vec<f64> = rows.iter().map(|r| r.2 as f64).collect();
    let contacts: Vec<f64> = rows.iter().map(|r| r.0 as f64).collect();
    println!(
        "{spheres},{per_side},{steps},fc3d,{name},{tol:e},{},{},{},{:.5},{:.5},{},{},{},{:.3e},{:.3},{:.3},{}",
        rows.len(),
        median(&contacts),
        contacts.iter().fold(0.0_f64, |a, &b| a.max(b)),
        median(&times),
        times.iter().fold(0.0_f64, |a, &b| a.max(b)),
        median(&its),
        its.iter().fold(0.0_f64, |a, &b| a.max(b)),
        rows.iter().filter(|r| !r.3).count(),
        rows.iter().fold(0.0_f64, |a, r| a.max(r.4)),
        times.iter().sum::<f64>(),
        total.elapsed().as_secs_f64(),
        load_average()
    );
    Ok(())
}

/// One CSV table: the header's names and the rows.
fn number(s: &str) -> Option<f64> {
    s.parse::<f64>().ok().filter(|v| v.is_finite())
}

fn run_report(args: &[String]) -> Result<(), String> {
    let opts = options(args)?;
    if let Some(path) = opts.get("csv") {
        print!("{}", solve_report(&Table::read(Path::new(path))?));
    }
    if let Some(path) = opts.get("settling") {
        print!("{}", settling_report(&Table::read(Path::new(path))?));
    }
    Ok(())
}

/// The time of a row that reached its tolerance.
fn time_reached(t: &Table, row: &[String]) -> Option<f64> {
    (t.get(row, "status") == "converged")
        .then(|| number(t.get(row, "cpu_s")))
        .flatten()
}

fn solve_report(t: &Table) -> String {
    // Scenes in order of appearance; tolerances loosest first.
    let mut scenes: Vec<(String, String)> = Vec::new();
    let mut tols: Vec<String> = Vec::new();
    for row in &t.rows {
        let scene = (t.get(row, "shape").into(), t.get(row, "contacts").into());
        if !scenes.contains(&scene) {
            scenes.push(scene);
        }
        let tol = t.get(row, "tolerance").to_string();
        if !tols.contains(&tol) {
            tols.push(tol);
        }
    }
    tols.sort_by(|a, b| {
        number(b)
            .unwrap_or(0.0)
            .total_cmp(&number(a).unwrap_or(0.0))
    });
    let mut out = String::from("| shape | contacts | library | method |");
    for tol in &tols {
        out += &format!(" to {tol}: CPU s | iterations | products |");
    }
    out += " error at the last tolerance run | solve peak MB | load |\n|---|---:|---|---|";
    out += &"---:|---:|---:|".repeat(tols.len());
    out += "---:|---:|---|\n";
    let mut summary = String::new();
    for (shape, contacts) in &scenes {
        let of_scene: Vec<&Vec<String>> = t
            .rows
            .iter()
            .filter(|r| t.get(r, "shape") == shape && t.get(r, "contacts") == contacts)
            .collect();
        let mut runs: Vec<(String, String)> = Vec::new();
        for r in &of_scene {
            let run = (t.get(r, "library").into(), t.get(r, "method").into());
            if !runs.contains(&run) {
                runs.push(run);
            }
        }
        // The best of each library per tolerance: (time, method).
        let mut best: BTreeMap<(String, String), (f64, String)> = BTreeMap::new();
        for r in &of_scene {
            if let Some(s) = time_reached(t, r) {
                let key = (t.get(r, "library").into(), t.get(r, "tolerance").into());
                let entry = best.entry(key).or_insert((f64::INFINITY, String::new()));
                if s < entry.0 {
                    *entry = (s, t.get(r, "method").into());
                }
            }
        }
        for (library, method) in &runs {
            let mine: Vec<&&Vec<String>> = of_scene
                .iter()
                .filter(|r| t.get(r, "library") == library && t.get(r, "method") == method)
                .collect();
            let mut line = format!("| {shape} | {contacts} | {library} | {method} |");
            let mut last_error = String::from("–");
            let mut peak = String::from("–");
            let mut load = String::from("–");
            for tol in &tols {
                let row = mine.iter().find(|r| t.get(r, "tolerance") == tol);
                let Some(row) = row else {
                    line += " – | | |";
                    continue;
                };
                let status = t.get(row, "status");
                if status == "not-run" {
                    line += " not run | | |";
                    continue;
                }
                last_error = t.get(row, "error").into();
                if let Some(p) = number(t.get(row, "solve_peak_mb")) {
                    peak = format!("{p:.0}");
                }
                load = t.get(row, "load").into();
                let is_best = best
                    .get(&(library.clone(), tol.clone()))
                    .is_some_and(|(_, m)| m == method);
                let time = match time_reached(t, row) {
                    Some(s) if is_best => format!("**{s:.3}**"),
                    Some(s) => format!("{s:.3}"),
                    None => match number(t.get(row, "cpu_s")) {
                        Some(s) => format!("> {s:.1} ({status})"),
                        None => status.to_string(),
                    },
                };
                line += &format!(
                    " {time} | {} | {} |",
                    t.get(row, "iterations"),
                    t.get(row, "products")
                );
            }
            line += &format!(" {last_error} | {peak} | {load} |\n");
            out += &line;
        }
        for tol in &tols {
            let fc3d = best.get(&("fc3d".into(), tol.clone()));
            let siconos = best.get(&("siconos".into(), tol.clone()));
            let text = match (fc3d, siconos) {
                (Some((a, ma)), Some((b, mb))) => format!(
                    "fc3d {ma} {a:.3} s, Siconos {mb} {b:.3} s: ratio {:.2}",
                    a / b
                ),
                (Some((a, ma)), None) => {
                    format!("fc3d {ma} {a:.3} s, no Siconos solver run reached it")
                }
                (None, Some((b, mb))) => {
                    format!("no fc3d method reached it, Siconos {mb} {b:.3} s")
                }
                (None, None) => "neither library reached it".into(),
            };
            summary += &format!("- {shape}, {contacts} contacts, to {tol}: {text}\n");
        }
    }
    out + "\nBest of each library (CPU seconds to the tolerance, set-up included):\n\n" + &summary
}

fn settling_report(t: &Table) -> String {
    let mut out = String::from(
        "\n| spheres | bin | steps solved | contacts (median, max) | library | method | tolerance | \
         median step CPU s | max step CPU s | median iterations | max iterations | \
         steps not converged | max error | load |\n\
         |---:|---:|---:|---|---|---|---:|---:|---:|---:|---:|---:|---:|---|\n",
    );
    for r in &t.rows {
        out += &format!(
            "| {} | {}x{} | {} | {}, {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
            t.get(r, "spheres"),
            t.get(r, "per_side"),
            t.get(r, "per_side"),
            t.get(r, "solved_steps"),
            t.get(r, "median_contacts"),
            t.get(r, "max_contacts"),
            t.get(r, "library"),
            t.get(r, "method"),
            t.get(r, "tolerance"),
            t.get(r, "median_step_s"),
            t.get(r, "max_step_s"),
            t.get(r, "median_iterations"),
            t.get(r, "max_iterations"),
            t.get(r, "not_converged"),
            t.get(r, "max_error"),
            t.get(r, "load"),
        );
    }
    out
}
