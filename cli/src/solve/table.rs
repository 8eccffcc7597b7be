//! The result table of `fc3d solve`, printed row by row with fixed widths.

use std::time::Duration;

use crate::units::{format_time, scientific};
use fc3d_core::SolveStatus;

/// A row of the result table.
pub(crate) struct Row {
    pub problem: String,
    pub contacts: usize,
    /// W's storage, or `global (M <storage>)` for a global problem.
    pub storage: String,
    pub solver: String,
    pub status: SolveStatus,
    pub iterations: usize,
    pub error: f64,
    pub time: Duration,
}

/// Fixed-width table printed row by row.
pub(crate) struct Table {
    header_done: bool,
}

const HEADERS: [&str; 8] = [
    "problem",
    "contacts",
    "storage",
    "solver",
    "iterations",
    "error",
    "status",
    "time",
];
const WIDTHS: [usize; 8] = [36, 8, 12, 9, 10, 9, 9, 10];

impl Table {
    pub(crate) fn new() -> Self {
        Table { header_done: false }
    }

    pub(crate) fn push(&mut self, row: Row) -> Vec<String> {
        let mut lines = Vec::new();
        if !self.header_done {
            self.header_done = true;
            lines.push(format_cells(&HEADERS.map(String::from)));
            lines.push(format_cells(&WIDTHS.map(|w| "-".repeat(w))));
        }
        let status = row.status.name();
        lines.push(format_cells(&[
            row.problem,
            row.contacts.to_string(),
            row.storage,
            row.solver,
            row.iterations.to_string(),
            scientific(row.error),
            status.to_string(),
            format_time(row.time),
        ]));
        lines
    }
}

/// Text columns left-aligned, the others right-aligned; a cell wider than its column widens it.
fn format_cells(cells: &[String; 8]) -> String {
    let mut s = String::new();
    for (k, (cell, &w)) in cells.iter().zip(WIDTHS.iter()).enumerate() {
        if k > 0 {
            s.push_str("  ");
        }
        let left = matches!(k, 0 | 2 | 3 | 6);
        if left {
            s.push_str(&format!("{cell:<w$}"));
        } else {
            s.push_str(&format!("{cell:>w$}"));
        }
    }
    s.trim_end().to_string()
}
