//! Report of AUTO against Siconos' solvers at equal time budget
//! (`scripts/compare-siconos-budget.sh`).
//!
//! ```text
//! budget_report <budget.csv> [--tie X] [--svg FILE] [--auto SOLVER]
//! ```
//!
//! Reads the CSV written by the script (columns problem, library, solver, budget_s, info,
//! iterations, limit, seconds, error_fc3d, error_siconos; one row per problem, solver and budget:
//! the run kept for that budget) and prints, in Markdown, per budget:
//!
//! * on how many problems AUTO's error is at most the best Siconos solver's (the smallest error
//!   of any Siconos solver within that budget, chosen per problem after the fact), scored by
//!   fc3d's `fc3d_compute_error` (`error_fc3d`); the same count scored by Siconos'
//!   `fc3d_compute_error` as a cross-check; and, when the CSV has other fc3d solvers, the same
//!   against the best of them;
//! * the problems where AUTO is behind: both errors, the winning solver, its iteration limit and
//!   time;
//! * which Siconos solver is the best how often.
//!
//! Tie rule: AUTO's error `a` is at most the best `b` when `a <= max(b, tie)` (default tie
//! 1e-14): two errors at round-off level count as equal (both libraries' error of the same
//! reaction differ by up to ~1e-16, and a solver that stopped at the tolerance 1e-14 is solved).
//! A solver with no run within the budget (or a timeout, crash, NaN) has error +inf; AUTO with
//! no result within the budget is behind unless no Siconos solver has one either.
//!
//! `--svg FILE` draws AUTO's error against the best Siconos error, one point per problem and
//! budget (log axes, errors below 1e-17 drawn at 1e-17, the diagonal = equal error).
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::process::ExitCode;

/// The run kept for one (problem, solver, budget).
#[derive(Clone, Debug)]
struct Kept {
    problem: String,
    library: String,
    solver: String,
    budget: f64,
    info: String,
    limit: String,
    seconds: Option<f64>,
    error_fc3d: f64,
    error_siconos: f64,
}

fn parse_error(s: &str) -> f64 {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v >= 0.0 => v,
        _ => f64::INFINITY,
    }
}

fn read_csv(path: &str) -> Result<Vec<Kept>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let mut rows = Vec::new();
    for (i, line) in text.lines().enumerate().skip(1) {
        if line.trim().is_empty() {
            continue;
        }
        let f: Vec<&str> = line.split(',').collect();
        if f.len() != 10 {
            return Err(format!("{path}:{}: {} fields, expected 10", i + 1, f.len()));
        }
        let budget = f[3]
            .parse::<f64>()
            .map_err(|e| format!("{path}:{}: budget {}: {e}", i + 1, f[3]))?;
        rows.push(Kept {
            problem: f[0].into(),
            library: f[1].into(),
            solver: f[2].into(),
            budget,
            info: f[4].into(),
            limit: f[6].into(),
            seconds: f[7].parse().ok(),
            error_fc3d: parse_error(f[8]),
            error_siconos: parse_error(f[9]),
        });
    }
    Ok(rows)
}

/// Which scorer's error is compared.
#[derive(Clone, Copy, PartialEq)]
enum Scorer {
    Fc3d,
    Siconos,
}

impl Kept {
    fn error(&self, scorer: Scorer) -> f64 {
        match scorer {
            Scorer::Fc3d => self.error_fc3d,
            Scorer::Siconos => self.error_siconos,
        }
    }
}

/// The smallest error among `rows` (+inf when none) and the row reaching it.
fn best<'a>(rows: impl Iterator<Item = &'a Kept>, scorer: Scorer) -> (f64, Option<&'a Kept>) {
    rows.fold((f64::INFINITY, None), |(e, r), k| {
        if k.error(scorer) < e {
            (k.error(scorer), Some(k))
        } else {
            (e, r)
        }
    })
}

/// AUTO's error is at most the other's, errors up to `tie` counting as equal.
fn at_most(auto: f64, other: f64, tie: f64) -> bool {
    auto <= other.max(tie)
}

fn fmt_err(e: f64) -> String {
    if e.is_finite() {
        format!("{e:.2e}")
    } else {
        "none".into()
    }
}

fn budget_label(b: f64) -> String {
    if b >= 1.0 {
        format!("{b} s")
    } else if b >= 1e-3 {
        format!("{} ms", (b * 1e3 * 1e6).round() / 1e6)
    } else {
        format!("{} us", (b * 1e6 * 1e3).round() / 1e3)
    }
}

/// Per budget and problem: AUTO's row and the Siconos and other fc3d rows.
struct Group<'a> {
    auto: Option<&'a Kept>,
    siconos: Vec<&'a Kept>,
    fc3d_others: Vec<&'a Kept>,
}

fn groups<'a>(rows: &'a [Kept], auto_solver: &str) -> BTreeMap<u64, BTreeMap<&'a str, Group<'a>>> {
    let mut out: BTreeMap<u64, BTreeMap<&str, Group>> = BTreeMap::new();
    for k in rows {
        let g = out
            .entry(k.budget.to_bits())
            .or_default()
            .entry(k.problem.as_str())
            .or_insert_with(|| Group {
                auto: None,
                siconos: Vec::new(),
                fc3d_others: Vec::new(),
            });
        if k.library == "siconos" {
            g.siconos.push(k);
        } else if k.solver == auto_solver {
            g.auto = Some(k);
        } else {
            g.fc3d_others.push(k);
        }
    }
    out
}

/// One point of the picture: (budget, best Siconos error, AUTO's error).
type Point = (f64, f64, f64);

fn report(rows: &[Kept], tie: f64, auto_solver: &str) -> (String, Vec<Point>) {
    let mut s = String::new();
    let mut points = Vec::new();
    let by_budget = groups(rows, auto_solver);
    let n_siconos = {
        let mut v: Vec<&str> = rows
            .iter()
            .filter(|k| k.library == "siconos")
            .map(|k| k.solver.as_str())
            .collect();
        v.sort_unstable();
        v.dedup();
        v.len()
    };
    let n_others = {
        let mut v: Vec<&str> = rows
            .iter()
            .filter(|k| k.library == "fc3d" && k.solver != auto_solver)
            .map(|k| k.solver.as_str())
            .collect();
        v.sort_unstable();
        v.dedup();
        v.len()
    };
    let _ = writeln!(
        s,
        "# AUTO ({auto_solver}) against {n_siconos} Siconos solvers at equal budget\n\n\
         AUTO's error <= the best Siconos solver's (per problem, the smallest error any of them \
         reaches within the budget), errors <= {tie:e} counted equal; scored by fc3d's \
         fc3d_compute_error, and by Siconos' as a cross-check.\n"
    );
    let mut header = "| budget | problems | AUTO <= best Siconos | without the tie rule | \
                      scored by Siconos | AUTO has no result | Siconos has none |"
        .to_string();
    let mut sep = "| --- | --- | --- | --- | --- | --- | --- |".to_string();
    if n_others > 0 {
        header += &format!(" AUTO <= best of {n_others} other fc3d solvers |");
        sep += " --- |";
    }
    let _ = writeln!(s, "{header}\n{sep}");
    let mut details = String::new();
    for (bits, problems) in &by_budget {
        let budget = f64::from_bits(*bits);
        let (mut ok, mut raw, mut ok_siconos, mut no_auto, mut no_siconos, mut ok_others) =
            (0, 0, 0, 0, 0, 0);
        let mut behind = Vec::new();
        let mut winners: BTreeMap<&str, usize> = BTreeMap::new();
        for (problem, g) in problems {
            let a = g.auto.map_or(f64::INFINITY, |k| k.error_fc3d);
            let a_sic = g.auto.map_or(f64::INFINITY, |k| k.error_siconos);
            let (b, b_row) = best(g.siconos.iter().copied(), Scorer::Fc3d);
            let (b_sic, _) = best(g.siconos.iter().copied(), Scorer::Siconos);
            let (o, _) = best(g.fc3d_others.iter().copied(), Scorer::Fc3d);
            if let Some(r) = b_row {
                *winners.entry(r.solver.as_str()).or_default() += 1;
            }
            no_auto += usize::from(!a.is_finite());
            no_siconos += usize::from(!b.is_finite());
            ok_siconos += usize::from(at_most(a_sic, b_sic, tie));
            raw += usize::from(a <= b);
            ok_others += usize::from(at_most(a, o, tie));
            if at_most(a, b, tie) {
                ok += 1;
            } else {
                behind.push((problem, g.auto, a, b, b_row));
            }
            points.push((budget, b, a));
        }
        let n = problems.len();
        let frac = |k: usize| format!("{k}/{n} ({:.2})", k as f64 / n.max(1) as f64);
        let mut line = format!(
            "| {} | {n} | {} | {} | {} | {no_auto} | {no_siconos} |",
            budget_label(budget),
            frac(ok),
            frac(raw),
            frac(ok_siconos)
        );
        if n_others > 0 {
            line += &format!(" {} |", frac(ok_others));
        }
        let _ = writeln!(s, "{line}");

        let _ = writeln!(details, "\n## {}\n", budget_label(budget));
        let mut w: Vec<(&str, usize)> = winners.into_iter().collect();
        w.sort_by(|x, y| y.1.cmp(&x.1).then(x.0.cmp(y.0)));
        let _ = writeln!(
            details,
            "Best Siconos solver (problems): {}\n",
            w.iter()
                .map(|(k, c)| format!("{k} {c}"))
                .collect::<Vec<_>>()
                .join(", ")
        );
        if behind.is_empty() {
            let _ = writeln!(details, "AUTO is behind on no problem.");
            continue;
        }
        let _ = writeln!(
            details,
            "| AUTO behind on | AUTO's error | AUTO's time | best Siconos | its error | ratio | its limit | its time |\n\
             | --- | --- | --- | --- | --- | --- | --- | --- |"
        );
        for (problem, auto, a, b, b_row) in behind {
            let r = b_row.expect("AUTO behind means some Siconos solver has a result");
            let _ = writeln!(
                details,
                "| {problem} | {} | {} | {} | {} | {} | {} | {} |",
                fmt_err(a),
                auto.and_then(|k| k.seconds)
                    .map_or("-".into(), |t| format!("{:.3} ms", t * 1e3)),
                r.solver,
                fmt_err(b),
                if a.is_finite() {
                    format!("{:.1}x", a / b.max(1e-300))
                } else {
                    "-".into()
                },
                r.limit,
                r.seconds
                    .map_or("-".into(), |t| format!("{:.3} ms", t * 1e3)),
            );
        }
    }
    s += &details;

    // The cross-check of the two scorers on every reaction both scored.
    let (mut worst_abs, mut worst_rel, mut pairs) = (0.0_f64, 0.0_f64, 0usize);
    for k in rows {
        if k.error_fc3d.is_finite() && k.error_siconos.is_finite() {
            pairs += 1;
            let d = (k.error_fc3d - k.error_siconos).abs();
            worst_abs = worst_abs.max(d);
            let m = k.error_fc3d.max(k.error_siconos);
            if m > 1e-12 {
                worst_rel = worst_rel.max(d / m);
            }
        }
    }
    // Per (library, solver, outcome): the problems, each counted once over the budgets.
    let mut failures: BTreeMap<(&str, &str, &str), std::collections::BTreeSet<&str>> =
        BTreeMap::new();
    for k in rows
        .iter()
        .filter(|k| k.info != "none" && k.info.parse::<i32>().is_err())
    {
        failures
            .entry((k.library.as_str(), k.solver.as_str(), k.info.as_str()))
            .or_default()
            .insert(k.problem.as_str());
    }
    let failed: Vec<String> = failures
        .iter()
        .map(|((library, solver, info), problems)| {
            format!("{library} {solver} {info} on {} problems", problems.len())
        })
        .collect();
    let _ = writeln!(
        s,
        "\n## Checks\n\nThe two libraries' fc3d_compute_error of the same {pairs} reactions: largest \
         difference {worst_abs:.1e} (relative {worst_rel:.1e} where an error exceeds 1e-12).\n\n\
         Runs that did not complete (timeout, crash, failed): {}",
        if failed.is_empty() {
            "none".into()
        } else {
            failed.join("; ")
        }
    );
    (s, points)
}

/// The scatter of AUTO's error against the best Siconos error, one colour per budget.
fn svg(points: &[Point]) -> String {
    const FLOOR: f64 = 1e-17;
    const TOP: f64 = 1.0;
    let (w, h, m) = (560.0, 520.0, 70.0);
    let span = (TOP.log10() - FLOOR.log10()) as f64;
    let px = |e: f64| m + (e.clamp(FLOOR, TOP).log10() - FLOOR.log10()) / span * (w - 1.5 * m);
    let py = |e: f64| h - m - (e.clamp(FLOOR, TOP).log10() - FLOOR.log10()) / span * (h - 1.5 * m);
    let colours = [
        "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b",
    ];
    let mut budgets: Vec<f64> = points.iter().map(|p| p.0).collect();
    budgets.sort_by(f64::total_cmp);
    budgets.dedup();
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-family=\"sans-serif\" font-size=\"12\">\n\
         <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n\
         <text x=\"{}\" y=\"20\" text-anchor=\"middle\" font-size=\"14\">AUTO against the best Siconos solver at equal budget</text>\n",
        w / 2.0
    );
    let (x0, x1, y0, y1) = (px(FLOOR), px(TOP), py(FLOOR), py(TOP));
    let _ = writeln!(
        s,
        "<rect x=\"{x0}\" y=\"{y1}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"black\"/>",
        x1 - x0,
        y0 - y1
    );
    for e in (-17..=0).step_by(2) {
        let v = 10f64.powi(e);
        let (x, y) = (px(v), py(v));
        let _ = writeln!(
            s,
            "<line x1=\"{x}\" y1=\"{y0}\" x2=\"{x}\" y2=\"{y1}\" stroke=\"#ddd\"/>\
             <line x1=\"{x0}\" y1=\"{y}\" x2=\"{x1}\" y2=\"{y}\" stroke=\"#ddd\"/>\
             <text x=\"{x}\" y=\"{}\" text-anchor=\"middle\">1e{e}</text>\
             <text x=\"{}\" y=\"{}\" text-anchor=\"end\">1e{e}</text>",
            y0 + 16.0,
            x0 - 6.0,
            y + 4.0
        );
    }
    let _ = writeln!(
        s,
        "<line x1=\"{x0}\" y1=\"{y0}\" x2=\"{x1}\" y2=\"{y1}\" stroke=\"black\" stroke-dasharray=\"4 3\"/>\n\
         <text x=\"{}\" y=\"{}\" text-anchor=\"middle\">best Siconos solver's error (below the diagonal: AUTO better)</text>\n\
         <text x=\"16\" y=\"{}\" text-anchor=\"middle\" transform=\"rotate(-90 16 {})\">AUTO's error</text>",
        (x0 + x1) / 2.0,
        y0 + 36.0,
        (y0 + y1) / 2.0,
        (y0 + y1) / 2.0
    );
    for (i, b) in budgets.iter().enumerate() {
        let c = colours[i % colours.len()];
        for p in points.iter().filter(|p| p.0 == *b) {
            let _ = writeln!(
                s,
                "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"4\" fill=\"none\" stroke=\"{c}\" stroke-width=\"1.5\"/>",
                px(p.1),
                py(p.2)
            );
        }
        let ly = y1 + 16.0 + 16.0 * i as f64;
        let _ = writeln!(
            s,
            "<circle cx=\"{}\" cy=\"{}\" r=\"4\" fill=\"none\" stroke=\"{c}\" stroke-width=\"1.5\"/>\
             <text x=\"{}\" y=\"{}\">{}</text>",
            x0 + 14.0,
            ly - 4.0,
            x0 + 24.0,
            ly,
            budget_label(*b)
        );
    }
    s += "</svg>\n";
    s
}

fn run() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut path = None;
    let (mut tie, mut svg_path, mut auto_solver) = (1e-14, None, "590".to_string());
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut value = |name: &str| it.next().cloned().ok_or(format!("{name} needs a value"));
        match a.as_str() {
            "--tie" => tie = value("--tie")?.parse().map_err(|e| format!("--tie: {e}"))?,
            "--svg" => svg_path = Some(value("--svg")?),
            "--auto" => auto_solver = value("--auto")?,
            _ if path.is_none() && !a.starts_with("--") => path = Some(a.clone()),
            _ => return Err(format!("unknown argument {a}")),
        }
    }
    let path =
        path.ok_or("usage: budget_report <budget.csv> [--tie X] [--svg FILE] [--auto SOLVER]")?;
    let rows = read_csv(&path)?;
    let (text, points) = report(&rows, tie, &auto_solver);
    print!("{text}");
    if let Some(p) = svg_path {
        std::fs::write(&p, svg(&points)).map_err(|e| format!("{p}: {e}"))?;
    }
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("budget_report: {e}");
            ExitCode::from(2)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kept(problem: &str, library: &str, solver: &str, budget: f64, e: f64) -> Kept {
        Kept {
            problem: problem.into(),
            library: library.into(),
            solver: solver.into(),
            budget,
            info: "1".into(),
            limit: "8".into(),
            seconds: Some(budget / 2.0),
            error_fc3d: e,
            error_siconos: e,
        }
    }

    #[test]
    fn tie_rule_and_missing_results() {
        assert!(at_most(1e-15, 1e-16, 1e-14));
        assert!(!at_most(2e-14, 1e-14, 1e-14));
        assert!(at_most(1e-6, 1e-6, 0.0));
        assert!(at_most(f64::INFINITY, f64::INFINITY, 1e-14));
        assert!(!at_most(f64::INFINITY, 1.0, 1e-14));
        assert_eq!(parse_error(""), f64::INFINITY);
        assert_eq!(parse_error("nan"), f64::INFINITY);
    }

    #[test]
    fn counts_per_budget() {
        let rows = vec![
            kept("a", "fc3d", "590", 0.01, 1e-6),
            kept("a", "siconos", "500", 0.01, 1e-5),
            kept("a", "siconos", "502", 0.01, 1e-7),
            kept("b", "fc3d", "590", 0.01, 1e-15),
            kept("b", "siconos", "500", 0.01, 1e-16),
        ];
        let (text, points) = report(&rows, 1e-14, "590");
        assert!(
            text.contains("| 10 ms | 2 | 1/2 (0.50) | 0/2 (0.00) |"),
            "{text}"
        );
        assert!(text.contains("| a | 1.00e-6 |"), "{text}");
        assert_eq!(points.len(), 2);
        assert!(svg(&points).starts_with("<svg"));
    }
}
