//! Pictures of `fc3d bench`, each written as SVG and PNG: performance profiles and
//! work–precision curves.
//!
//! Text is laid out with ab_glyph from Noto Sans embedded in the binary (crate `ttf-noto-sans`),
//! so PNG text needs no system font library; the SVG names the `sans-serif` family and leaves the
//! glyphs to the viewer. PNGs are encoded with the `png` crate from plotters' RGB buffer.

use std::path::{Path, PathBuf};
use std::sync::Once;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::profile::PerformanceProfile;

/// Picture size in pixels (SVG user units and PNG pixels).
const SIZE: (u32, u32) = (960, 640);
/// Font family registered with plotters and used for every text.
const FONT: &str = "sans-serif";
/// Smallest error drawn on a log axis (exact solutions, error 0, are drawn there).
pub const ERROR_FLOOR: f64 = 1e-17;
/// Smallest time drawn on a log axis, seconds.
const TIME_FLOOR: f64 = 1e-7;

/// Colour-blind-safe colours (Okabe-Ito), then a few more.
const COLORS: [RGBColor; 10] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
    RGBColor(240, 228, 66),
    RGBColor(140, 86, 75),
    RGBColor(127, 127, 127),
];

fn color(k: usize) -> RGBColor {
    COLORS[k % COLORS.len()]
}

/// Point markers: solver `k` gets colour `k mod 10` and marker `k div 10`, so that 40 solvers
/// have distinct (colour, marker) pairs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Marker {
    Circle,
    Triangle,
    Square,
    Cross,
}

const MARKERS: [Marker; 4] = [
    Marker::Circle,
    Marker::Triangle,
    Marker::Square,
    Marker::Cross,
];

fn marker(k: usize) -> Marker {
    MARKERS[(k / COLORS.len()) % MARKERS.len()]
}

/// Draws `marker` of `size` pixels at each point of a chart.
fn draw_markers<DB: DrawingBackend, CT: plotters::coord::CoordTranslate<From = (f64, f64)>>(
    chart: &mut ChartContext<'_, DB, CT>,
    points: &[(f64, f64)],
    marker: Marker,
    size: i32,
    style: ShapeStyle,
) -> Result<(), String> {
    let at = points.iter().copied();
    match marker {
        Marker::Circle => chart
            .draw_series(at.map(|p| Circle::new(p, size, style)))
            .map(|_| ()),
        Marker::Triangle => chart
            .draw_series(at.map(|p| TriangleMarker::new(p, size + 1, style)))
            .map(|_| ()),
        Marker::Square => chart
            .draw_series(at.map(|p| {
                EmptyElement::at(p) + Rectangle::new([(-size, -size), (size, size)], style)
            }))
            .map(|_| ()),
        Marker::Cross => chart
            .draw_series(at.map(|p| Cross::new(p, size + 1, style.stroke_width(2))))
            .map(|_| ()),
    }
    .map_err(err)
}

/// The marker at pixel `(x, y)` of a legend.
fn draw_legend_marker<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    (x, y): (i32, i32),
    marker: Marker,
    c: RGBColor,
) -> Result<(), String> {
    let style = c.filled();
    match marker {
        Marker::Circle => area.draw(&Circle::new((x, y), 5, style)),
        Marker::Triangle => area.draw(&TriangleMarker::new((x, y), 6, style)),
        Marker::Square => area.draw(&Rectangle::new([(x - 5, y - 5), (x + 5, y + 5)], style)),
        Marker::Cross => area.draw(&Cross::new((x, y), 6, c.stroke_width(2))),
    }
    .map_err(err)
}

/// Line width of curve `k` of `n`: the first drawn are the widest, so that a curve hidden under a
/// later one with the same values still shows at its edges.
fn width(k: usize, n: usize) -> u32 {
    (2 + n.saturating_sub(k + 1) as u32).min(6)
}

fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        if plotters::style::register_font(FONT, FontStyle::Normal, ttf_noto_sans::REGULAR).is_err()
        {
            // The embedded font is a fixed, valid TTF: this cannot happen short of a broken build.
            eprintln!("fc3d bench: the embedded font could not be loaded; pictures lack text");
        }
    });
}

/// Something drawable on any plotters backend.
pub trait Picture {
    /// Size in pixels.
    fn size(&self) -> (u32, u32);
    fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String>;
}

/// Height of one legend row, pixels.
const LEGEND_ROW: u32 = 26;
/// Legend entries per row.
const LEGEND_COLUMNS: usize = 2;

fn legend_height(entries: usize) -> u32 {
    let rows = entries.div_ceil(LEGEND_COLUMNS) as u32;
    rows * LEGEND_ROW + 16
}

/// Picture size with a legend of `entries` entries below the chart.
fn size_with_legend(entries: usize) -> (u32, u32) {
    (SIZE.0, SIZE.1 + legend_height(entries))
}

/// Splits `root` into the chart area and a legend strip below it, and draws the legend there
/// (outside the chart, so that it never hides data).
fn split_legend<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    entries: &[(String, RGBColor, Marker)],
) -> Result<DrawingArea<DB, Shift>, String> {
    let (w, h) = root.dim_in_pixel();
    let (chart, legend) = root.split_vertically(h - legend_height(entries.len()));
    let column = (w as i32 - 40) / LEGEND_COLUMNS as i32;
    for (k, (text, c, m)) in entries.iter().enumerate() {
        let x = 40 + (k % LEGEND_COLUMNS) as i32 * column;
        let y = 8 + (k / LEGEND_COLUMNS) as i32 * LEGEND_ROW as i32 + LEGEND_ROW as i32 / 2;
        legend
            .draw(&PathElement::new(
                vec![(x, y), (x + 28, y)],
                c.stroke_width(3),
            ))
            .map_err(err)?;
        draw_legend_marker(&legend, (x + 14, y), *m, *c)?;
        legend
            .draw(&Text::new(
                text.clone(),
                (x + 36, y),
                TextStyle::from((FONT, 16).into_font()).pos(Pos::new(HPos::Left, VPos::Center)),
            ))
            .map_err(err)?;
    }
    Ok(chart)
}

fn err<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

/// Writes `<dir>/<stem>.svg` and `<dir>/<stem>.png`; returns both paths.
pub fn save<P: Picture>(picture: &P, dir: &Path, stem: &str) -> Result<Vec<PathBuf>, String> {
    register_font();
    let svg = dir.join(format!("{stem}.svg"));
    let png = dir.join(format!("{stem}.png"));
    let size = picture.size();
    {
        let root = SVGBackend::new(&svg, size).into_drawing_area();
        picture.draw(&root)?;
        root.present()
            .map_err(|e| format!("{}: {e}", svg.display()))?;
    }
    let mut buffer = vec![0u8; size.0 as usize * size.1 as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, size).into_drawing_area();
        picture.draw(&root)?;
        root.present().map_err(err)?;
    }
    write_png(&png, &buffer, size).map_err(|e| format!("{}: {e}", png.display()))?;
    Ok(vec![svg, png])
}

fn write_png(path: &Path, rgb: &[u8], (w, h): (u32, u32)) -> Result<(), String> {
    let file = std::fs::File::create(path).map_err(err)?;
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), w, h);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().map_err(err)?;
    writer.write_image_data(rgb).map_err(err)?;
    writer.finish().map_err(err)
}

/// A performance profile for one tolerance: `rho_s(tau)` against `log2 tau`.
pub struct ProfilePicture<'a> {
    pub title: String,
    pub profile: &'a PerformanceProfile,
    pub solver_names: &'a [String],
}

impl ProfilePicture<'_> {
    fn legend(&self) -> Vec<(String, RGBColor, Marker)> {
        (0..self.profile.n_solvers())
            .map(|s| {
                let text = format!(
                    "{}   ρ(1) = {:.2}, solved {:.0}%",
                    self.solver_names[s],
                    self.profile.rho(s, 1.0),
                    100.0 * self.profile.robustness(s)
                );
                (text, color(s), marker(s))
            })
            .collect()
    }
}

impl Picture for ProfilePicture<'_> {
    fn size(&self) -> (u32, u32) {
        size_with_legend(self.profile.n_solvers())
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        root.fill(&WHITE).map_err(err)?;
        let root = &split_legend(root, &self.legend())?;
        // Right end of the axis: past the largest finite ratio, so that every step shows.
        let log2_max = (self.profile.max_ratio().log2() * 1.05).max(1.0);
        let tau_max = log2_max.exp2();
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, (FONT, 24))
            .margin(16)
            .x_label_area_size(50)
            .y_label_area_size(64)
            .build_cartesian_2d(0f64..log2_max, 0f64..1.02f64)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("log2(τ): time within a factor τ of the fastest solver")
            .y_desc("ρ_s(τ): share of problems")
            .axis_desc_style((FONT, 18))
            .label_style((FONT, 15))
            .draw()
            .map_err(err)?;
        for s in 0..self.profile.n_solvers() {
            let points: Vec<(f64, f64)> = self
                .profile
                .steps(s, tau_max)
                .into_iter()
                .map(|(tau, rho)| (tau.log2().min(log2_max), rho))
                .collect();
            chart
                .draw_series(LineSeries::new(
                    points.clone(),
                    color(s).stroke_width(width(s, self.profile.n_solvers())),
                ))
                .map_err(err)?;
            // A marker at each step's corner tells apart curves of the same colour.
            draw_markers(&mut chart, &points, marker(s), 4, color(s).filled())?;
        }
        Ok(())
    }
}

/// One solver's curve on a work–precision picture.
pub struct Curve {
    pub name: String,
    /// The curve: (time s, error) per tolerance or budget, in order.
    pub points: Vec<(f64, f64)>,
    /// Individual runs, drawn as faint dots.
    pub runs: Vec<(f64, f64)>,
}

/// Achieved error against time (or any positive quantity against another), log–log, one
/// curve per solver or series.
pub struct WorkPrecisionPicture {
    pub title: String,
    pub x_desc: String,
    pub y_desc: String,
    pub curves: Vec<Curve>,
}

/// The y axis of the bench's work–precision pictures.
pub const ERROR_DESC: &str = "achieved error (relative natural map)";

fn log_range(values: impl Iterator<Item = f64>, floor: f64) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite()) {
        let v = v.max(floor);
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return (floor, floor * 10.0);
    }
    // Whole decades around the data, one more where a value sits on a decade (it would be drawn
    // on the frame).
    let (lo, hi) = (
        10f64.powf((lo.log10() - 0.05).floor()),
        10f64.powf((hi.log10() + 0.05).ceil()),
    );
    if hi > lo {
        (lo, hi)
    } else {
        (lo, lo * 10.0)
    }
}

/// The error axis: whole decades around the positive errors and, when some error is exactly 0,
/// one more decade below whose upper line (returned) is the row of the zeros.
fn error_axis(errors: impl Iterator<Item = f64>) -> (f64, f64, Option<f64>) {
    let errors: Vec<f64> = errors.filter(|e| e.is_finite()).collect();
    let (lo, hi) = log_range(errors.iter().copied().filter(|&e| e > 0.0), ERROR_FLOOR);
    if errors.iter().any(|&e| e <= 0.0) {
        (lo / 100.0, hi, Some(lo / 10.0))
    } else {
        (lo, hi, None)
    }
}

impl Picture for WorkPrecisionPicture {
    fn size(&self) -> (u32, u32) {
        size_with_legend(self.curves.len())
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        root.fill(&WHITE).map_err(err)?;
        let legend: Vec<(String, RGBColor, Marker)> = self
            .curves
            .iter()
            .enumerate()
            .map(|(s, c)| (c.name.clone(), color(s), marker(s)))
            .collect();
        let root = &split_legend(root, &legend)?;
        let all = || {
            self.curves
                .iter()
                .flat_map(|c| c.points.iter().chain(&c.runs))
        };
        let (x0, x1) = log_range(all().map(|p| p.0), TIME_FLOOR);
        let (y0, y1, zero_row) = error_axis(all().map(|p| p.1));
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, (FONT, 24))
            .margin(16)
            .x_label_area_size(50)
            .y_label_area_size(80)
            .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc(&self.x_desc)
            .y_desc(&self.y_desc)
            .axis_desc_style((FONT, 18))
            .label_style((FONT, 15))
            .x_label_formatter(&|x| format!("{x:.0e}"))
            .y_label_formatter(&|y| match zero_row {
                Some(z) if (y / z - 1.0).abs() < 1e-6 => "0".to_string(),
                Some(z) if *y < z => String::new(),
                _ => format!("{y:.0e}"),
            })
            .draw()
            .map_err(err)?;
        // Errors of exactly 0 are drawn on the row labelled 0, a decade below the smallest
        // positive error.
        let clamp = |&(x, y): &(f64, f64)| {
            let y = match zero_row {
                Some(z) if y <= 0.0 => z,
                _ => y.max(ERROR_FLOOR),
            };
            (x.max(TIME_FLOOR), y)
        };
        for (s, curve) in self.curves.iter().enumerate() {
            let c = color(s);
            chart
                .draw_series(
                    curve
                        .runs
                        .iter()
                        .map(clamp)
                        .map(|p| Circle::new(p, 2, c.mix(0.35).filled())),
                )
                .map_err(err)?;
            let points: Vec<(f64, f64)> = curve.points.iter().map(clamp).collect();
            chart
                .draw_series(LineSeries::new(
                    points.clone(),
                    c.stroke_width(width(s, self.curves.len())),
                ))
                .map_err(err)?;
            draw_markers(&mut chart, &points, marker(s), 4, c.filled())?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_ranges_are_whole_decades() {
        assert_eq!(log_range([2e-5, 3e-3].into_iter(), 1e-9), (1e-5, 1e-2));
        assert_eq!(log_range([0.0, 1e-10].into_iter(), 1e-17), (1e-18, 1e-9));
        assert_eq!(log_range([f64::INFINITY].into_iter(), 1e-7), (1e-7, 1e-6));
        let (lo, hi) = log_range([1e-3].into_iter(), 1e-9);
        assert!(hi > lo);
    }

    #[test]
    fn zero_errors_get_their_own_row_below_the_data() {
        assert_eq!(error_axis([2e-5, 3e-3].into_iter()), (1e-5, 1e-2, None));
        let (lo, hi, zero) = error_axis([0.0, 2e-5, 3e-3].into_iter());
        assert_eq!(hi, 1e-2);
        let zero = zero.unwrap();
        assert!((zero / 1e-6 - 1.0).abs() < 1e-12 && (lo / 1e-7 - 1.0).abs() < 1e-12);
        // Only zeros: the floor's decades.
        let (lo, _, zero) = error_axis([0.0].into_iter());
        assert!(zero.unwrap() > lo);
    }

    #[test]
    fn forty_solvers_have_distinct_colour_and_marker() {
        let styles: Vec<(RGBColor, Marker)> = (0..40).map(|k| (color(k), marker(k))).collect();
        for i in 0..40 {
            for j in 0..i {
                assert_ne!(styles[i], styles[j], "{i} and {j}");
            }
        }
    }
}
