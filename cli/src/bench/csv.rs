//! One CSV row per run (RFC 4180: comma-separated, a field holding a comma, a quote or a line
//! break is quoted with its quotes doubled; numbers in Rust's shortest round-trip notation).
//!
//! Columns (docs/benchmarks.md documents them for users):
//!
//! | column | meaning |
//! | --- | --- |
//! | `mode` | `tolerance` (run until the tolerance) or `budget` (run until the time budget) |
//! | `problem` | file name or built-in scene name |
//! | `family` | problem family: file-name prefix before the first digit or dash (scene: its name) |
//! | `contacts` | number of contacts |
//! | `solver` | solver label, e.g. `NSGS/565` |
//! | `tolerance` | tolerance asked for (relative natural-map error) |
//! | `time_budget_s` | wall-clock budget of the run: `--timeout` or the `--budget` value |
//! | `max_iter` | iteration limit |
//! | `status` | `converged`, `max-iter` or `out-of-time` |
//! | `info` | Siconos' info: 0 converged, 1 max-iter, 2 out-of-time |
//! | `iterations` | iterations (sweeps) done |
//! | `error` | error recomputed by the bench from the returned r (`u = W r + q`) |
//! | `reported_error` | the error the solver reported |
//! | `error_check` | `ok` when both agree within rounding, `MISMATCH` otherwise |
//! | `time_s` | median over the repetitions of the solve call's wall-clock time, seconds |
//! | `reps` | repetitions run (fewer than `--reps` when the first ran out of time) |

use std::io::{self, Write};

/// What one (problem, solver, tolerance or budget) run produced.
#[derive(Debug, Clone, PartialEq)]
pub struct RunRecord {
    pub mode: &'static str,
    pub problem: String,
    pub family: String,
    pub contacts: usize,
    pub solver: String,
    pub tolerance: f64,
    pub time_budget_s: f64,
    pub max_iter: usize,
    pub status: &'static str,
    pub info: i32,
    pub iterations: usize,
    pub error: f64,
    pub reported_error: f64,
    pub error_ok: bool,
    pub time_s: f64,
    pub reps: usize,
}

impl RunRecord {
    pub fn converged(&self) -> bool {
        self.info == 0
    }
}

pub const HEADER: [&str; 16] = [
    "mode",
    "problem",
    "family",
    "contacts",
    "solver",
    "tolerance",
    "time_budget_s",
    "max_iter",
    "status",
    "info",
    "iterations",
    "error",
    "reported_error",
    "error_check",
    "time_s",
    "reps",
];

/// A field as CSV: quoted when it holds a comma, a quote or a line break.
pub fn field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

fn number(x: f64) -> String {
    format!("{x:e}")
}

fn row(r: &RunRecord) -> [String; 16] {
    [
        r.mode.to_string(),
        field(&r.problem),
        field(&r.family),
        r.contacts.to_string(),
        field(&r.solver),
        number(r.tolerance),
        number(r.time_budget_s),
        r.max_iter.to_string(),
        r.status.to_string(),
        r.info.to_string(),
        r.iterations.to_string(),
        number(r.error),
        number(r.reported_error),
        if r.error_ok { "ok" } else { "MISMATCH" }.to_string(),
        number(r.time_s),
        r.reps.to_string(),
    ]
}

/// Writes the header line and one line per record.
pub fn write_csv<W: Write>(records: &[RunRecord], out: &mut W) -> io::Result<()> {
    writeln!(out, "{}", HEADER.join(","))?;
    for r in records {
        writeln!(out, "{}", row(r).join(","))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record() -> RunRecord {
        RunRecord {
            mode: "tolerance",
            problem: "Rover1039.dat".into(),
            family: "Rover".into(),
            contacts: 4,
            solver: "NSGS/565".into(),
            tolerance: 1e-8,
            time_budget_s: 20.0,
            max_iter: 100_000,
            status: "converged",
            info: 0,
            iterations: 20,
            error: 3.0123e-11,
            reported_error: 3.0123e-11,
            error_ok: true,
            time_s: 3.21e-5,
            reps: 3,
        }
    }

    #[test]
    fn header_and_rows() {
        let mut other = record();
        other.problem = "odd, \"name\".dat".into();
        other.status = "out-of-time";
        other.info = 2;
        other.error_ok = false;
        other.error = f64::INFINITY;
        let mut buf = Vec::new();
        write_csv(&[record(), other], &mut buf).unwrap();
        let text = String::from_utf8(buf).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 3);
        assert_eq!(
            lines[0],
            "mode,problem,family,contacts,solver,tolerance,time_budget_s,max_iter,status,info,\
             iterations,error,reported_error,error_check,time_s,reps"
        );
        assert_eq!(
            lines[1],
            "tolerance,Rover1039.dat,Rover,4,NSGS/565,1e-8,2e1,100000,converged,0,20,3.0123e-11,\
             3.0123e-11,ok,3.21e-5,3"
        );
        assert_eq!(
            lines[2],
            "tolerance,\"odd, \"\"name\"\".dat\",Rover,4,NSGS/565,1e-8,2e1,100000,out-of-time,2,\
             20,inf,3.0123e-11,MISMATCH,3.21e-5,3"
        );
        // Numbers read back exactly.
        let cells: Vec<&str> = lines[1].split(',').collect();
        assert_eq!(cells.len(), HEADER.len());
        assert_eq!(cells[11].parse::<f64>().unwrap(), 3.0123e-11);
        assert_eq!(cells[14].parse::<f64>().unwrap(), 3.21e-5);
    }

    #[test]
    fn quoting() {
        assert_eq!(field("plain"), "plain");
        assert_eq!(field("a,b"), "\"a,b\"");
        assert_eq!(field("say \"x\""), "\"say \"\"x\"\"\"");
        assert_eq!(field("two\nlines"), "\"two\nlines\"");
    }
}
