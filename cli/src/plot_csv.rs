//! `fc3d plot RESULTS.csv --x COLUMN --y COLUMN [--by COLUMN] [--where COLUMN=VALUE]... -o STEM`:
//! draws one column of a benchmark CSV against another, log–log, one curve per value of `--by`
//! (in the order of first appearance), as `STEM.svg` and `STEM.png`, with the pictures of
//! `fc3d bench` (the same colours, markers and legend). Rows whose x or y is not a positive
//! number (`-`, `NaN`, empty) are left out; `--where` keeps the rows whose column holds the value
//! (repeatable, all must hold). The CSV is the plain kind the benchmarks write
//! ([`crate::plain_csv`]).
//!
//! The pictures of docs/convergence.md are drawn with it (the commands are beside them).
//!
//! Exit status: 0 when the picture was written, 1 when the CSV could not be read or holds no
//! point to draw, 2 on a command-line error.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use crate::bench::plot::{save, Curve, WorkPrecisionPicture};
use crate::plain_csv::Table;

#[derive(Args, Debug, Clone, PartialEq)]
pub struct PlotArgs {
    /// The CSV file (a header line, then comma-separated rows).
    #[arg(value_name = "CSV")]
    pub csv: PathBuf,
    /// Column of the horizontal axis.
    #[arg(long, value_name = "COLUMN")]
    pub x: String,
    /// Column of the vertical axis.
    #[arg(long, value_name = "COLUMN")]
    pub y: String,
    /// Column whose values name the curves (default: one curve of every row).
    #[arg(long, value_name = "COLUMN")]
    pub by: Option<String>,
    /// Keep only the rows where COLUMN holds VALUE (repeatable).
    #[arg(long = "where", value_name = "COLUMN=VALUE", value_parser = parse_filter)]
    pub filters: Vec<(String, String)>,
    /// Picture title (default: "Y against X").
    #[arg(long)]
    pub title: Option<String>,
    /// Label of the horizontal axis (default: the column's name).
    #[arg(long, value_name = "TEXT")]
    pub x_label: Option<String>,
    /// Label of the vertical axis (default: the column's name).
    #[arg(long, value_name = "TEXT")]
    pub y_label: Option<String>,
    /// Text in front of each curve's name in the legend (e.g. "mu x ").
    #[arg(long, value_name = "TEXT", default_value = "")]
    pub legend_prefix: String,
    /// Output path without extension: STEM.svg and STEM.png are written.
    #[arg(short, long, value_name = "STEM")]
    pub output: PathBuf,
}

fn parse_filter(s: &str) -> Result<(String, String), String> {
    s.split_once('=')
        .map(|(c, v)| (c.trim().to_string(), v.trim().to_string()))
        .ok_or_else(|| format!("'{s}' is not COLUMN=VALUE"))
}

/// The curves of `table` under `args`: (name, points) in order of first appearance.
fn curves(table: &Table, args: &PlotArgs) -> Result<Vec<Curve>, String> {
    let (x, y) = (table.column(&args.x)?, table.column(&args.y)?);
    let by = args.by.as_deref().map(|c| table.column(c)).transpose()?;
    let filters = args
        .filters
        .iter()
        .map(|(c, v)| Ok((table.column(c)?, v.as_str())))
        .collect::<Result<Vec<_>, String>>()?;
    let positive = |s: &str| s.parse::<f64>().ok().filter(|v| v.is_finite() && *v > 0.0);
    let mut out: Vec<Curve> = Vec::new();
    for fields in &table.rows {
        let field = |k: usize| fields.get(k).map_or("", String::as_str);
        if filters.iter().any(|&(c, v)| field(c) != v) {
            continue;
        }
        let (Some(px), Some(py)) = (positive(field(x)), positive(field(y))) else {
            continue;
        };
        let name = format!("{}{}", args.legend_prefix, by.map_or("", field));
        match out.iter_mut().find(|c| c.name == name) {
            Some(curve) => curve.points.push((px, py)),
            None => out.push(Curve {
                name,
                points: vec![(px, py)],
                runs: Vec::new(),
            }),
        }
    }
    if out.is_empty() {
        return Err("no row has a positive x and y to draw".into());
    }
    Ok(out)
}

pub fn run(args: &PlotArgs) -> ExitCode {
    let drawn = Table::read(&args.csv)
        .and_then(|table| curves(&table, args))
        .and_then(|curves| {
            let picture = WorkPrecisionPicture {
                title: args
                    .title
                    .clone()
                    .unwrap_or_else(|| format!("{} against {}", args.y, args.x)),
                x_desc: args.x_label.clone().unwrap_or_else(|| args.x.clone()),
                y_desc: args.y_label.clone().unwrap_or_else(|| args.y.clone()),
                curves,
            };
            let dir = args.output.parent().unwrap_or(std::path::Path::new("."));
            let stem = args
                .output
                .file_name()
                .and_then(|s| s.to_str())
                .ok_or_else(|| format!("{}: not a file name", args.output.display()))?;
            save(&picture, dir, stem)
        });
    match drawn {
        Ok(paths) => {
            for p in paths {
                println!("{}", p.display());
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("fc3d plot: {e}");
            ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(by: Option<&str>, filters: &[(&str, &str)]) -> PlotArgs {
        PlotArgs {
            csv: PathBuf::new(),
            x: "sweep".into(),
            y: "error".into(),
            by: by.map(str::to_string),
            filters: filters
                .iter()
                .map(|(c, v)| (c.to_string(), v.to_string()))
                .collect(),
            title: None,
            x_label: None,
            y_label: None,
            legend_prefix: "mu x ".into(),
            output: PathBuf::from("out"),
        }
    }

    const CSV: &str = "shape,mu_scale,sweep,error\n\
                       spheres,0,1,0.3\nspheres,0,2,0.1\nspheres,1,1,0.31\n\
                       spheres,1,2,-\nboxes,0,1,0.2\n";

    #[test]
    fn rows_become_curves_in_order_of_first_appearance() {
        let table = Table::parse(CSV).unwrap();
        let c = curves(&table, &args(Some("mu_scale"), &[("shape", "spheres")])).unwrap();
        assert_eq!(c.len(), 2);
        assert_eq!(c[0].name, "mu x 0");
        assert_eq!(c[0].points, vec![(1.0, 0.3), (2.0, 0.1)]);
        // The row whose error is not a number is left out.
        assert_eq!(c[1].points, vec![(1.0, 0.31)]);
    }

    #[test]
    fn unknown_columns_and_empty_selections_are_refused() {
        let table = Table::parse(CSV).unwrap();
        let e = curves(&table, &args(Some("nope"), &[])).err().unwrap();
        assert!(e.contains("no column 'nope'"), "{e}");
        let e = curves(&table, &args(None, &[("shape", "cones")]))
            .err()
            .unwrap();
        assert!(e.contains("no row"), "{e}");
        assert!(parse_filter("shape").is_err());
    }
}
