//! `scale_report RESULTS.csv [--picture OUT.svg]`: the report of `scripts/scale-bench.sh`.
//!
//! Prints a Markdown table (one row per size and library: sweep time, its ratio to Siconos' sweep
//! at the same size and its memory-bandwidth floor, per-call set-up in seconds and in sweeps,
//! peak RSS of reading, what solving adds, the peak of both, bytes per contact, time and sweeps
//! to each tolerance) and,
//! with `--picture`, draws time per sweep and per-call set-up against contacts on log-log axes
//! (SVG, and PNG next to it), one series per library (the threaded fc3d rows, library
//! `fc3d-coloured-Nt`, are a series of their own). Times are CPU seconds, but for rows whose
//! `clock` column says `wall` (threaded runs: CPU time would sum the threads).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use plotters::prelude::*;

#[path = "../plain_csv.rs"]
mod plain_csv;
use plain_csv::Table;

struct Row {
    contacts: f64,
    library: String,
    fields: BTreeMap<String, String>,
}

impl Row {
    fn num(&self, key: &str) -> Option<f64> {
        self.fields
            .get(key)
            .and_then(|v| v.parse::<f64>().ok())
            .filter(|v| v.is_finite())
    }
}

fn read_rows(path: &Path) -> Result<(Vec<Row>, Vec<String>), String> {
    let table = Table::read(path)?;
    let mut rows = Vec::new();
    for line in &table.rows {
        let fields: BTreeMap<String, String> = table
            .columns
            .iter()
            .cloned()
            .zip(line.iter().cloned())
            .collect();
        let contacts = table.get(line, "contacts").parse().map_err(|_| {
            format!(
                "{}: a row without contacts: {}",
                path.display(),
                line.join(",")
            )
        })?;
        let library = table.get(line, "library").to_string();
        rows.push(Row {
            contacts,
            library,
            fields,
        });
    }
    let tols = table
        .columns
        .iter()
        .filter_map(|h| h.strip_prefix("t_").and_then(|t| t.strip_suffix("_s")))
        .map(str::to_string)
        .collect();
    Ok((rows, tols))
}

fn ms(v: Option<f64>) -> String {
    v.map_or("–".into(), |v| format!("{:.3}", v * 1e3))
}

fn mb(kb: Option<f64>) -> String {
    kb.map_or("–".into(), |v| format!("{:.0}", v / 1024.0))
}

/// The library whose sweep the others are compared with.
const REFERENCE_LIBRARY: &str = "siconos";

/// A row's library, marked when its times are wall-clock seconds.
fn library_label(r: &Row) -> String {
    match r.fields.get("clock").map(String::as_str) {
        Some("wall") => format!("{} (wall)", r.library),
        _ => r.library.clone(),
    }
}

/// The row's sweep time over the reference library's at the same size.
fn sweep_ratio(rows: &[Row], r: &Row) -> String {
    let reference = rows
        .iter()
        .find(|x| x.library == REFERENCE_LIBRARY && x.contacts == r.contacts)
        .and_then(|x| x.num("sweep_s"));
    match (r.num("sweep_s"), reference) {
        (Some(s), Some(s0)) if s0 > 0.0 => format!("{:.2}", s / s0),
        _ => "–".into(),
    }
}

fn table(rows: &[Row], tols: &[String]) -> String {
    let mut out = String::new();
    let mut head = format!(
        "| contacts | library | sweep ms | sweep / {REFERENCE_LIBRARY} | floor ms | set-up ms | \
         set-up / sweep | peak read MB | held after read MB | solve adds MB | peak read + solve MB \
         | bytes / contact |"
    );
    let mut rule = "|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|".to_string();
    for t in tols {
        head.push_str(&format!(" to {t}: s (sweeps) |"));
        rule.push_str("---:|");
    }
    out.push_str(&head);
    out.push('\n');
    out.push_str(&rule);
    out.push('\n');
    for r in rows {
        let sweep = r.num("sweep_s");
        let setup = r.num("setup_s").map(|s| s.max(0.0));
        let ratio = match (setup, sweep) {
            (Some(u), Some(s)) if s > 0.0 => format!("{:.2}", u / s),
            _ => "–".into(),
        };
        let held = r.num("rss_after_read_kb");
        // The solve's peak: of the calls stopped at their iteration limit and of the call that
        // converged, when measured (VmHWM was reset to the RSS before each, so both are
        // absolute).
        let peak_solve = match (r.num("peak_solve_kb"), r.num("peak_converged_kb")) {
            (Some(a), Some(b)) => Some(a.max(b)),
            (a, b) => a.or(b),
        };
        let adds = match (peak_solve, held) {
            (Some(p), Some(h)) => Some(p - h),
            _ => None,
        };
        // The process's peak over the read and the solve.
        let peak_all = match (r.num("peak_read_kb"), peak_solve) {
            (Some(a), Some(b)) => Some(a.max(b)),
            _ => None,
        };
        let per_contact = match (held, r.num("rss_before_kb")) {
            (Some(h), Some(b)) => format!("{:.0}", (h - b) * 1024.0 / r.contacts),
            _ => "–".into(),
        };
        let mut line = format!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.contacts,
            library_label(r),
            ms(sweep),
            sweep_ratio(rows, r),
            ms(r.num("floor_s")),
            ms(setup),
            ratio,
            mb(r.num("peak_read_kb")),
            mb(held),
            mb(adds),
            mb(peak_all),
            per_contact
        );
        for t in tols {
            let cell = match (r.num(&format!("t_{t}_s")), r.num(&format!("it_{t}"))) {
                (Some(s), Some(k)) => format!(" {s:.2} ({k}) |"),
                _ if r.fields.get("status").is_some_and(|s| s != "ok") => " > limit |".into(),
                _ => " – |".into(),
            };
            line.push_str(&cell);
        }
        out.push_str(&line);
        out.push('\n');
    }
    out
}

/// The libraries' colours, then the floor's (grey).
const COLORS: [RGBColor; 7] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(127, 127, 127),
];
const FLOOR_COLOR: RGBColor = COLORS[COLORS.len() - 1];

/// The series of the picture: (legend, colour, dashed, points).
type Series = (String, RGBColor, bool, Vec<(f64, f64)>);

fn series(rows: &[Row]) -> Vec<Series> {
    let mut out = Vec::new();
    let mut libraries: Vec<&str> = rows.iter().map(|r| r.library.as_str()).collect();
    libraries.dedup();
    // The single-thread libraries first (their colours as before threaded rows existed).
    libraries.sort_unstable_by_key(|l| (l.contains("coloured"), *l));
    libraries.dedup();
    for (k, lib) in libraries.iter().enumerate() {
        // Beyond the palette the colours repeat (the dashes still tell set-up from sweep).
        let color = COLORS[k % (COLORS.len() - 1)];
        let label = rows
            .iter()
            .find(|r| r.library == *lib)
            .map_or_else(|| lib.to_string(), library_label);
        let of = |key: &str| -> Vec<(f64, f64)> {
            rows.iter()
                .filter(|r| r.library == *lib)
                // A set-up measured as 0 or less (the difference of two noisy medians) has no
                // place on a log axis: left out rather than drawn at an arbitrary floor.
                .filter_map(|r| r.num(key).filter(|&v| v > 0.0).map(|v| (r.contacts, v)))
                .collect()
        };
        out.push((
            format!("{label}: time per sweep"),
            color,
            false,
            of("sweep_s"),
        ));
        out.push((
            format!("{label}: set-up per call"),
            color,
            true,
            of("setup_s"),
        ));
    }
    let floor: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.library == libraries.first().copied().unwrap_or(""))
        .filter_map(|r| r.num("floor_s").map(|v| (r.contacts, v)))
        .collect();
    out.push((
        "memory-bandwidth floor of a sweep".into(),
        FLOOR_COLOR,
        false,
        floor,
    ));
    out
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    series: &[Series],
) -> Result<(), String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(err)?;
    let xs = series.iter().flat_map(|s| s.3.iter().map(|p| p.0));
    let ys = series.iter().flat_map(|s| s.3.iter().map(|p| p.1));
    let decade = |v: f64, up: bool| {
        let l = v.log10();
        10f64.powf(if up { l.ceil() } else { l.floor() })
    };
    let (x0, x1) = xs.fold((f64::INFINITY, 0.0_f64), |(a, b), x| (a.min(x), b.max(x)));
    let (y0, y1) = ys.fold((f64::INFINITY, 0.0_f64), |(a, b), y| (a.min(y), b.max(y)));
    if !(x0.is_finite() && y0.is_finite()) {
        return Err("no data to draw".into());
    }
    let mut chart = ChartBuilder::on(root)
        .caption(
            "NSGS on sphere piles: time per sweep and per-call set-up",
            ("sans-serif", 24),
        )
        .margin(16)
        .x_label_area_size(50)
        .y_label_area_size(80)
        .build_cartesian_2d(
            (decade(x0, false)..decade(x1 * 1.01, true)).log_scale(),
            (decade(y0, false)..decade(y1 * 1.01, true)).log_scale(),
        )
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("contacts")
        .y_desc("seconds")
        .axis_desc_style(("sans-serif", 18))
        .label_style(("sans-serif", 15))
        .x_label_formatter(&|x| format!("{x:.0e}"))
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .draw()
        .map_err(err)?;
    for (name, color, dashed, points) in series {
        let style = color.stroke_width(3);
        let drawn = if *dashed {
            chart.draw_series(DashedLineSeries::new(points.clone(), 10, 6, style))
        } else {
            chart.draw_series(LineSeries::new(points.clone(), style))
        };
        drawn
            .map_err(err)?
            .label(name.clone())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 24, y)], color.stroke_width(3))
            });
        chart
            .draw_series(points.iter().map(|&p| Circle::new(p, 4, color.filled())))
            .map_err(err)?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .label_font(("sans-serif", 16))
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()
        .map_err(err)?;
    Ok(())
}

fn save(series: &[Series], svg: &Path) -> Result<PathBuf, String> {
    if plotters::style::register_font("sans-serif", FontStyle::Normal, ttf_noto_sans::REGULAR)
        .is_err()
    {
        eprintln!("scale_report: the embedded font could not be loaded; the PNG lacks text");
    }
    let size = (960, 640);
    {
        let root = SVGBackend::new(svg, size).into_drawing_area();
        draw(&root, series)?;
        root.present()
            .map_err(|e| format!("{}: {e}", svg.display()))?;
    }
    let png = svg.with_extension("png");
    let mut buffer = vec![0u8; (size.0 * size.1 * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, size).into_drawing_area();
        draw(&root, series)?;
        root.present().map_err(|e| e.to_string())?;
    }
    let file = std::fs::File::create(&png).map_err(|e| format!("{}: {e}", png.display()))?;
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), size.0, size.1);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().map_err(|e| e.to_string())?;
    writer
        .write_image_data(&buffer)
        .map_err(|e| e.to_string())?;
    writer.finish().map_err(|e| e.to_string())?;
    Ok(png)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (csv, picture) = match args.as_slice() {
        [csv] => (PathBuf::from(csv), None),
        [csv, flag, out] if flag == "--picture" => (PathBuf::from(csv), Some(PathBuf::from(out))),
        _ => {
            eprintln!("usage: scale_report RESULTS.csv [--picture OUT.svg]");
            return ExitCode::from(2);
        }
    };
    let (rows, tols) = match read_rows(&csv) {
        Ok(x) => x,
        Err(e) => {
            eprintln!("scale_report: {e}");
            return ExitCode::from(1);
        }
    };
    print!("{}", table(&rows, &tols));
    if rows
        .iter()
        .any(|r| r.fields.get("clock").is_some_and(|c| c == "wall"))
    {
        println!(
            "\nTimes are CPU seconds of the process, but for the rows marked (wall): threaded \
             runs, timed in wall-clock seconds (their CPU time sums the threads)."
        );
    }
    if let Some(bw) = rows.first().and_then(|r| r.num("bandwidth_gbs")) {
        println!(
            "\nFloor: bytes a sweep must read (W's blocks and column indices, row pointers, q, r, \
             mu) / the measured streaming read bandwidth ({bw:.2} GB/s)."
        );
    }
    if let Some(svg) = picture {
        match save(&series(&rows), &svg) {
            Ok(png) => println!("\nPicture: {} and {}", svg.display(), png.display()),
            Err(e) => {
                eprintln!("scale_report: {e}");
                return ExitCode::from(1);
            }
        }
    }
    ExitCode::SUCCESS
}
