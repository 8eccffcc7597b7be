//! Report of a side-by-side run of fc3d and Siconos Numerics 4.4 (`scripts/compare-siconos.sh`).
//!
//! ```text
//! compare_report <results.csv> [--check] [--rel-tol X] [--abs-floor X] [--exact-iterations LIST]
//! ```
//!
//! Reads the CSV written by the script (columns problem, solver, tol, library, info, iterations,
//! error_self, error_by_other, seconds, reps, error_self_rescored; two rows per comparison,
//! library `fc3d` and `siconos`) and prints, in Markdown:
//!
//! * per solver spec and tolerance: the problems solved (info >= 0 and own error `dparam[1]` <=
//!   tol) by each library, the geometric mean of the time ratio fc3d/Siconos over the problems
//!   both solve (also restricted to the problems where both take >= 1 ms, where per-call overhead
//!   no longer dominates), the worst (largest) ratio with its problem, and how many problems
//!   give the same iteration count;
//! * agreement: problems solved by one library only, iteration counts that differ, runs that did
//!   not complete (timeout, crash), and errors that disagree: a library's own `dparam[1]` against
//!   the other library's `fc3d_compute_error` of the same reaction (and against its own
//!   recomputation).
//!
//! Two errors `a`, `b` of the same reaction disagree when `|a - b| > rel_tol * max(a, b) +
//! abs_floor` (defaults 1e-6 and 1e-14), or when one is <= tol and the other is not. Both
//! libraries evaluate the same formula on the same bit-exact reaction (written with `%.17g`);
//! only the summation order of `W r + q` and of the norms differs, which moves the normalised
//! error by an absolute amount of the order of machine epsilon (at most 1.5e-16 over the 658
//! pairs of the full comparison). For a converged error of 1e-12 that is already a relative
//! difference of 1e-4, so a relative test alone would flag rounding; the floor 1e-14 is 100 times
//! the largest rounding seen and still 1e-6 of the usual tolerance 1e-8. The relative part
//! catches a different formula or normalisation, which changes an error by a factor, not by a
//! millionth of it.
//!
//! `--check` (the script's `--quick` mode): exit status 1 when the libraries disagree on any
//! comparison: a run that did not complete, a different info, a different iteration count for a
//! solver of `--exact-iterations` (default `500,500/565,500/552`: the solvers whose iteration
//! counts matched Siconos' on all 30 problems of the full comparison), for other solvers a pair
//! that is not "both converge and each library's error of the other's solution <= tol" (551
//! differs on one problem, where Siconos' local Goldstein-Price Newton stops short of the local
//! tolerance in the first sweep; 553 uses a different local iteration; 550's unglobalised Newton
//! diverges between the libraries on 9 problems), a solution accepted by its library and
//! rejected by the other's error, or errors that disagree as above. Times never fail a check.
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::process::ExitCode;

const LIBS: [&str; 2] = ["fc3d", "siconos"];
const LIB_NAMES: [&str; 2] = ["fc3d", "Siconos"];

/// One library's run of one comparison (one CSV row).
#[derive(Clone, Debug)]
struct Run {
    /// The driver's return code, or `timeout`, `crash:<signal>`, `failed`.
    info: Result<i32, String>,
    iterations: Option<u64>,
    error_self: Option<f64>,
    error_by_other: Option<f64>,
    seconds: Option<f64>,
    rescored: Option<f64>,
}

impl Run {
    fn completed(&self) -> bool {
        matches!(self.info, Ok(code) if code >= 0)
    }

    /// Solved by its own measure: info >= 0 and `dparam[1]` <= tol.
    fn solved(&self, tol: f64) -> bool {
        self.completed() && self.error_self.is_some_and(|e| e <= tol)
    }

    fn short(&self) -> String {
        match &self.info {
            Ok(code) => format!(
                "info {code}, {} it, error {}",
                self.iterations.map_or("?".to_string(), |k| k.to_string()),
                fmt_err(self.error_self)
            ),
            Err(status) => status.clone(),
        }
    }
}

/// One comparison: a problem, a solver spec, a tolerance, and the two libraries' runs.
struct Comparison {
    problem: String,
    solver: String,
    tol_text: String,
    tol: f64,
    runs: [Option<Run>; 2],
}

struct Criteria {
    rel_tol: f64,
    abs_floor: f64,
    exact: Vec<String>,
}

impl Criteria {
    fn disagree(&self, a: f64, b: f64) -> bool {
        (a - b).abs() > self.rel_tol * a.abs().max(b.abs()) + self.abs_floor
    }
}

fn fmt_err(e: Option<f64>) -> String {
    e.map_or("-".to_string(), |e| format!("{e:.3e}"))
}

fn parse_opt<T: std::str::FromStr>(
    field: &str,
    what: &str,
    line: usize,
) -> Result<Option<T>, String> {
    if field.is_empty() {
        return Ok(None);
    }
    field
        .parse()
        .map(Some)
        .map_err(|_| format!("line {line}: bad {what} {field:?}"))
}

fn read_csv(path: &str) -> Result<Vec<Comparison>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let mut lines = text.lines().enumerate();
    let header = lines.next().map(|(_, h)| h).unwrap_or("");
    if !header
        .starts_with("problem,solver,tol,library,info,iterations,error_self,error_by_other,seconds")
    {
        return Err(format!(
            "{path}: not a compare-siconos CSV (header {header:?})"
        ));
    }
    let mut comparisons: Vec<Comparison> = Vec::new();
    let mut index: BTreeMap<(String, String, String), usize> = BTreeMap::new();
    for (i, line) in lines {
        let n = i + 1;
        if line.trim().is_empty() {
            continue;
        }
        let f: Vec<&str> = line.split(',').collect();
        if f.len() < 9 {
            return Err(format!(
                "{path}:{n}: {} fields, expected at least 9",
                f.len()
            ));
        }
        let lib = LIBS
            .iter()
            .position(|l| *l == f[3])
            .ok_or_else(|| format!("{path}:{n}: unknown library {:?}", f[3]))?;
        let tol: f64 = f[2]
            .parse()
            .map_err(|_| format!("{path}:{n}: bad tolerance {:?}", f[2]))?;
        let info = match f[4].parse::<i32>() {
            Ok(code) => Ok(code),
            Err(_) if !f[4].is_empty() => Err(f[4].to_string()),
            Err(_) => return Err(format!("{path}:{n}: empty info")),
        };
        let run = Run {
            info,
            iterations: parse_opt(f[5], "iterations", n)?,
            error_self: parse_opt(f[6], "error_self", n)?,
            error_by_other: parse_opt(f[7], "error_by_other", n)?,
            seconds: parse_opt(f[8], "seconds", n)?,
            rescored: match f.get(10) {
                Some(x) => parse_opt(x, "error_self_rescored", n)?,
                None => None,
            },
        };
        let key = (f[0].to_string(), f[1].to_string(), f[2].to_string());
        let at = *index.entry(key).or_insert_with(|| {
            comparisons.push(Comparison {
                problem: f[0].to_string(),
                solver: f[1].to_string(),
                tol_text: f[2].to_string(),
                tol,
                runs: [None, None],
            });
            comparisons.len() - 1
        });
        comparisons[at].runs[lib] = Some(run);
    }
    Ok(comparisons)
}

/// Distinct values in order of first appearance.
fn distinct<'a>(items: impl Iterator<Item = &'a str>) -> Vec<&'a str> {
    let mut out: Vec<&str> = Vec::new();
    for item in items {
        if !out.contains(&item) {
            out.push(item);
        }
    }
    out
}

fn report(path: &str, comparisons: &[Comparison], criteria: &Criteria) -> String {
    let mut s = String::new();
    let problems = distinct(comparisons.iter().map(|c| c.problem.as_str()));
    let specs = distinct(comparisons.iter().map(|c| c.solver.as_str()));
    let tols = distinct(comparisons.iter().map(|c| c.tol_text.as_str()));
    let _ = writeln!(s, "# fc3d vs Siconos Numerics 4.4: {path}\n");
    let _ = writeln!(
        s,
        "{} problems x {} solver specs ({}) x {} tolerances ({}). Solved: info >= 0 and the \
         library's own error (dparam[1]) <= tol. Time ratio: fc3d seconds / Siconos seconds \
         (median fc3d_driver time), over the problems both solve; < 1 means fc3d is faster.\n",
        problems.len(),
        specs.len(),
        specs.join(", "),
        tols.len(),
        tols.join(", ")
    );

    let _ = writeln!(s, "## Summary\n");
    let _ = writeln!(
        s,
        "| solver | tol | problems | solved by fc3d | solved by Siconos | both | time ratio fc3d/Siconos (geometric mean) | geometric mean, runs >= 1 ms (problems) | worst ratio (problem) | same iterations |"
    );
    let _ = writeln!(
        s,
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
    );
    for spec in &specs {
        for tol in &tols {
            let group: Vec<&Comparison> = comparisons
                .iter()
                .filter(|c| c.solver == *spec && c.tol_text == *tol)
                .collect();
            if group.is_empty() {
                continue;
            }
            let solved = |lib: usize| {
                group
                    .iter()
                    .filter(|c| c.runs[lib].as_ref().is_some_and(|r| r.solved(c.tol)))
                    .count()
            };
            // (ratio, problem, shorter of the two times)
            let mut ratios: Vec<(f64, &str, f64)> = Vec::new();
            let (mut same_it, mut both_ran) = (0, 0);
            for c in &group {
                let (Some(a), Some(b)) = (&c.runs[0], &c.runs[1]) else {
                    continue;
                };
                if a.completed() && b.completed() {
                    both_ran += 1;
                    if a.iterations == b.iterations {
                        same_it += 1;
                    }
                }
                if a.solved(c.tol) && b.solved(c.tol) {
                    if let (Some(ta), Some(tb)) = (a.seconds, b.seconds) {
                        if ta > 0.0 && tb > 0.0 {
                            ratios.push((ta / tb, c.problem.as_str(), ta.min(tb)));
                        }
                    }
                }
            }
            let geo =
                geo_mean(ratios.iter().map(|x| x.0)).map_or("-".to_string(), |g| format!("{g:.2}"));
            let long: Vec<f64> = ratios.iter().filter(|x| x.2 >= 1e-3).map(|x| x.0).collect();
            let geo_long = geo_mean(long.iter().copied())
                .map_or("-".to_string(), |g| format!("{g:.2} ({})", long.len()));
            let worst = ratios
                .iter()
                .max_by(|x, y| x.0.total_cmp(&y.0))
                .map_or("-".to_string(), |(r, p, _)| format!("{r:.2} ({p})"));
            let _ = writeln!(
                s,
                "| {spec} | {tol} | {} | {} | {} | {} | {geo} | {geo_long} | {worst} | {same_it}/{both_ran} |",
                group.len(),
                solved(0),
                solved(1),
                ratios.len()
            );
        }
    }

    let _ = writeln!(s, "\n## Agreement\n");
    let _ = writeln!(s, "### Solved by one library only\n");
    pair_table(&mut s, comparisons, |c, a, b| {
        a.solved(c.tol) != b.solved(c.tol)
    });

    let _ = writeln!(
        s,
        "### Iteration counts that differ (both runs completed)\n"
    );
    pair_table(&mut s, comparisons, |_, a, b| {
        a.completed() && b.completed() && (a.iterations != b.iterations || a.info != b.info)
    });

    let _ = writeln!(s, "### Runs that did not complete\n");
    let mut rows = Vec::new();
    for c in comparisons {
        for (lib, run) in c.runs.iter().enumerate() {
            match run {
                None => rows.push(format!(
                    "| {} | {} | {} | {} | missing |",
                    c.solver, c.tol_text, c.problem, LIB_NAMES[lib]
                )),
                Some(r) if !r.completed() => rows.push(format!(
                    "| {} | {} | {} | {} | {} |",
                    c.solver,
                    c.tol_text,
                    c.problem,
                    LIB_NAMES[lib],
                    r.short()
                )),
                _ => {}
            }
        }
    }
    table(
        &mut s,
        "| solver | tol | problem | library | status |\n| --- | --- | --- | --- | --- |",
        &rows,
    );

    let _ = writeln!(
        s,
        "### Errors of the same reaction that disagree\n\nOwn error (dparam[1]) against the other \
         library's fc3d_compute_error of the returned reaction and against the library's own \
         recomputation; disagreement: |a - b| > {:e} max(a, b) + {:e}.\n",
        criteria.rel_tol, criteria.abs_floor
    );
    let mut rows = Vec::new();
    let (mut checked, mut worst_rel) = (0usize, (0.0f64, String::new()));
    for c in comparisons {
        for (lib, run) in c.runs.iter().enumerate() {
            let Some(r) = run else { continue };
            let Some(own) = r.error_self.filter(|_| r.completed()) else {
                continue;
            };
            for (label, other) in [
                ("other library", r.error_by_other),
                ("own recomputation", r.rescored),
            ] {
                let Some(other) = other else { continue };
                checked += 1;
                let rel = (own - other).abs() / own.abs().max(other.abs()).max(f64::MIN_POSITIVE);
                if own.max(other) > criteria.abs_floor && rel > worst_rel.0 {
                    worst_rel = (
                        rel,
                        format!("{} {} {} ({label})", c.problem, c.solver, LIB_NAMES[lib]),
                    );
                }
                let flips = (own <= c.tol) != (other <= c.tol);
                if criteria.disagree(own, other) || flips {
                    rows.push(format!(
                        "| {} | {} | {} | {} | {own:.6e} | {label}: {other:.6e} | {:.1e} |{}",
                        c.solver,
                        c.tol_text,
                        c.problem,
                        LIB_NAMES[lib],
                        rel,
                        if flips { " verdict differs" } else { "" }
                    ));
                }
            }
        }
    }
    table(
        &mut s,
        "| solver | tol | problem | solution of | own error | other error | relative difference |\n| --- | --- | --- | --- | --- | --- | --- |",
        &rows,
    );
    let _ = writeln!(
        s,
        "{checked} error pairs compared; largest relative difference among errors above the floor: {:.1e} ({}).\n",
        worst_rel.0,
        if worst_rel.1.is_empty() { "-" } else { &worst_rel.1 }
    );
    s
}

/// Geometric mean, None for an empty sequence.
fn geo_mean(values: impl Iterator<Item = f64>) -> Option<f64> {
    let (mut sum, mut n) = (0.0, 0usize);
    for v in values {
        sum += v.ln();
        n += 1;
    }
    (n > 0).then(|| (sum / n as f64).exp())
}

/// A table of the comparisons whose two runs (fc3d, Siconos) satisfy `keep`, side by side.
fn pair_table(
    s: &mut String,
    comparisons: &[Comparison],
    keep: impl Fn(&Comparison, &Run, &Run) -> bool,
) {
    let rows: Vec<String> = comparisons
        .iter()
        .filter_map(|c| match (&c.runs[0], &c.runs[1]) {
            (Some(a), Some(b)) if keep(c, a, b) => Some(format!(
                "| {} | {} | {} | {} | {} |",
                c.solver,
                c.tol_text,
                c.problem,
                a.short(),
                b.short()
            )),
            _ => None,
        })
        .collect();
    table(
        s,
        "| solver | tol | problem | fc3d | Siconos |\n| --- | --- | --- | --- | --- |",
        &rows,
    );
}

fn table(s: &mut String, header: &str, rows: &[String]) {
    if rows.is_empty() {
        let _ = writeln!(s, "none\n");
    } else {
        let _ = writeln!(s, "{header}");
        for r in rows {
            let _ = writeln!(s, "{r}");
        }
        let _ = writeln!(s);
    }
}

/// The `--check` verdict: one line per comparison where the libraries disagree.
fn check(comparisons: &[Comparison], criteria: &Criteria) -> Vec<String> {
    let mut failures = Vec::new();
    for c in comparisons {
        let what = format!("{} {} tol {}", c.problem, c.solver, c.tol_text);
        let (Some(a), Some(b)) = (&c.runs[0], &c.runs[1]) else {
            failures.push(format!("{what}: a library's run is missing"));
            continue;
        };
        if !a.completed() || !b.completed() {
            failures.push(format!(
                "{what}: did not complete: fc3d [{}] Siconos [{}]",
                a.short(),
                b.short()
            ));
            continue;
        }
        if a.info != b.info {
            failures.push(format!(
                "{what}: different info: fc3d [{}] Siconos [{}]",
                a.short(),
                b.short()
            ));
        }
        if a.iterations != b.iterations {
            let exact = criteria.exact.contains(&c.solver);
            let loose_ok = a.solved(c.tol)
                && b.solved(c.tol)
                && a.error_by_other.is_some_and(|e| e <= c.tol)
                && b.error_by_other.is_some_and(|e| e <= c.tol);
            if exact {
                failures.push(format!(
                    "{what}: different iteration counts: fc3d [{}] Siconos [{}]",
                    a.short(),
                    b.short()
                ));
            } else if !loose_ok {
                failures.push(format!(
                    "{what}: iteration counts differ and not both converged with each error of the other's solution <= tol: fc3d [{}] Siconos [{}]",
                    a.short(),
                    b.short()
                ));
            }
        }
        for (lib, r) in [a, b].into_iter().enumerate() {
            let (Some(own), Some(other)) = (r.error_self, r.error_by_other) else {
                failures.push(format!(
                    "{what}: {} solution not scored by the other library",
                    LIB_NAMES[lib]
                ));
                continue;
            };
            if (own <= c.tol) != (other <= c.tol) {
                failures.push(format!(
                    "{what}: {} solution: own error {own:.6e}, other library's {other:.6e}: verdicts differ",
                    LIB_NAMES[lib]
                ));
            } else if criteria.disagree(own, other) {
                failures.push(format!(
                    "{what}: {} solution: own error {own:.6e}, other library's {other:.6e}",
                    LIB_NAMES[lib]
                ));
            }
        }
    }
    failures
}

fn run() -> Result<bool, String> {
    let mut args = std::env::args().skip(1);
    let mut path = None;
    let mut do_check = false;
    let mut criteria = Criteria {
        rel_tol: 1e-6,
        abs_floor: 1e-14,
        exact: ["500", "500/565", "500/552"].map(String::from).to_vec(),
    };
    let number = |v: Option<String>, what: &str| -> Result<f64, String> {
        v.as_deref()
            .and_then(|x| x.parse().ok())
            .ok_or_else(|| format!("{what} needs a number"))
    };
    while let Some(a) = args.next() {
        match a.as_str() {
            "--check" => do_check = true,
            "--rel-tol" => criteria.rel_tol = number(args.next(), "--rel-tol")?,
            "--abs-floor" => criteria.abs_floor = number(args.next(), "--abs-floor")?,
            "--exact-iterations" => {
                let list = args.next().ok_or("--exact-iterations needs a list")?;
                criteria.exact = list
                    .split([',', ' '])
                    .filter(|x| !x.is_empty())
                    .map(String::from)
                    .collect();
            }
            "-h" | "--help" => {
                println!(
                    "usage: compare_report <results.csv> [--check] [--rel-tol X] [--abs-floor X] [--exact-iterations LIST]"
                );
                return Ok(true);
            }
            _ if path.is_none() && !a.starts_with("--") => path = Some(a),
            _ => return Err(format!("unexpected argument {a:?} (see --help)")),
        }
    }
    let path = path.ok_or("usage: compare_report <results.csv> [--check] (see --help)")?;
    let comparisons = read_csv(&path)?;
    if comparisons.is_empty() {
        return Err(format!("{path}: no results"));
    }
    print!("{}", report(&path, &comparisons, &criteria));
    if !do_check {
        return Ok(true);
    }
    let failures = check(&comparisons, &criteria);
    println!("## Check\n");
    println!(
        "Same info; same iterations for {}; otherwise both converge and each library's error of \
         the other's solution <= tol; errors of the same reaction agree (criterion above); \
         times are not checked.\n",
        criteria.exact.join(", ")
    );
    if failures.is_empty() {
        println!("agreement: all {} comparisons agree", comparisons.len());
        Ok(true)
    } else {
        for f in &failures {
            println!("DISAGREEMENT {f}");
        }
        println!(
            "\n{} disagreement(s) over {} comparisons",
            failures.len(),
            comparisons.len()
        );
        Ok(false)
    }
}

fn main() -> ExitCode {
    match run() {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(e) => {
            eprintln!("compare_report: {e}");
            ExitCode::from(2)
        }
    }
}
