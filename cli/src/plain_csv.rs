//! The plain CSV the benchmark scripts write and their reports read: a header line, then
//! comma-separated fields, no quoting; blank lines are skipped and fields trimmed. One reader
//! for `fc3d plot` and the report binaries (`convergence_bench`, `scale_report`, which include
//! this file).
// Each includer uses a part of it.
#![allow(dead_code)]

use std::path::Path;

/// A CSV file's columns and rows (each row's fields in the columns' order; a short row lacks
/// its last fields).
pub struct Table {
    pub columns: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

impl Table {
    /// Reads and parses the file at `path` (errors name it).
    pub fn read(path: &Path) -> Result<Table, String> {
        let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
        Table::parse(&text).map_err(|e| format!("{}: {e}", path.display()))
    }

    /// Parses CSV text; fails only when it holds no header.
    pub fn parse(text: &str) -> Result<Table, String> {
        let split = |line: &str| line.split(',').map(|f| f.trim().to_string()).collect();
        let mut lines = text.lines().filter(|l| !l.trim().is_empty());
        let columns = split(lines.next().ok_or("empty")?);
        let rows = lines.map(split).collect();
        Ok(Table { columns, rows })
    }

    /// The index of the column `name`.
    pub fn column(&self, name: &str) -> Result<usize, String> {
        self.index(name)
            .ok_or_else(|| format!("no column '{name}' (columns: {})", self.columns.join(", ")))
    }

    /// The field of `row` in column `name` ("" when the column or the field is missing).
    pub fn get<'a>(&self, row: &'a [String], name: &str) -> &'a str {
        self.index(name)
            .and_then(|i| row.get(i))
            .map_or("", String::as_str)
    }

    fn index(&self, name: &str) -> Option<usize> {
        self.columns.iter().position(|c| c == name)
    }
}
