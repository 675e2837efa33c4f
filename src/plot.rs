//! Small PNG line plots on `plotters`: a [`Figure`] of several [`Panel`]s laid out in a grid,
//! each panel with axis titles, a legend and labelled [`Series`].
//!
//! Text needs a TrueType font at run time (plotters' `ab_glyph` backend): the font is read once
//! from `$CFRD_FONT` or, failing that, from the usual DejaVu Sans locations (Debian package
//! `fonts-dejavu-core`). A missing font is a [`PlotError::Font`], not a panic.
//!
//! ```no_run
//! use cfrd::plot::{Figure, Panel, Series};
//! let panel = Panel::new("Direct shear", "shear displacement (mm)", "tau (kPa)")
//!     .with(Series::line("sigma_n = 100 kPa", vec![(0.0, 0.0), (5.0, 22.5), (30.0, 63.0)]));
//! Figure::new("Hyperbolic interface").with(panel).save_png("shear.png".as_ref()).unwrap();
//! ```

use plotters::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use thiserror::Error;

/// Environment variable naming a TTF font file to use instead of the default search.
pub const FONT_ENV: &str = "CFRD_FONT";
/// Where the default font is looked for (Debian `fonts-dejavu-core` first).
pub const FONT_PATHS: [&str; 4] = [
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
    "/usr/local/share/fonts/DejaVuSans.ttf",
];
/// Family name under which the font is registered with plotters.
const FAMILY: &str = "sans-serif";

/// A plot that could not be written.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum PlotError {
    /// No usable TrueType font.
    #[error("no usable TrueType font for plots: {0}")]
    Font(String),
    /// Drawing or encoding failed.
    #[error("{path}: cannot write plot: {message}")]
    Draw {
        /// The PNG being written.
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SeriesStyle {
    /// A polyline through the points.
    #[default]
    Line,
    /// A small circle at each point.
    Markers,
    /// Separate straight segments between the points 0–1, 2–3, … (vector plots).
    Segments,
}

/// One labelled data series of a panel.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend label (empty: not in the legend).
    pub label: String,
    /// Points (x, y); non-finite points are skipped.
    pub points: Vec<(f64, f64)>,
    /// Line or markers.
    pub style: SeriesStyle,
}

impl Series {
    /// A line series.
    pub fn line(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            label: label.into(),
            points,
            style: SeriesStyle::Line,
        }
    }

    /// A series of separate segments (`points` in pairs: tail, head).
    pub fn segments(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            label: label.into(),
            points,
            style: SeriesStyle::Segments,
        }
    }

    /// A marker series.
    pub fn markers(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            label: label.into(),
            points,
            style: SeriesStyle::Markers,
        }
    }
}

/// One chart: title, axis titles and its series.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Panel {
    /// Caption above the chart.
    pub title: String,
    /// Title of the x axis (with units).
    pub x_label: String,
    /// Title of the y axis (with units).
    pub y_label: String,
    /// The data.
    pub series: Vec<Series>,
    /// Legend in the lower right corner instead of the upper left (for data that crowd the
    /// upper left, e.g. costly runs with large errors).
    pub legend_lower_right: bool,
}

impl Panel {
    /// An empty panel.
    pub fn new(title: impl Into<String>, x_label: impl Into<String>, y_label: impl Into<String>) -> Self {
        Panel {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            series: Vec::new(),
            legend_lower_right: false,
        }
    }

    /// Puts the legend in the lower right corner (builder style).
    pub fn legend_lower_right(mut self) -> Self {
        self.legend_lower_right = true;
        self
    }

    /// Adds a series (builder style).
    pub fn with(mut self, series: Series) -> Self {
        self.series.push(series);
        self
    }

    /// Adds a series.
    pub fn push(&mut self, series: Series) {
        self.series.push(series);
    }

    /// Bounds (x_min, x_max, y_min, y_max) of the finite points, padded by 5 %; a degenerate
    /// range is widened so that the axis stays drawable.
    fn bounds(&self) -> (f64, f64, f64, f64) {
        let mut b = [f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY];
        for (x, y) in self.series.iter().flat_map(|s| s.points.iter()) {
            if x.is_finite() && y.is_finite() {
                b = [b[0].min(*x), b[1].max(*x), b[2].min(*y), b[3].max(*y)];
            }
        }
        let pad = |lo: f64, hi: f64| -> (f64, f64) {
            if !lo.is_finite() {
                return (0.0, 1.0);
            }
            let span = hi - lo;
            let mag = lo.abs().max(hi.abs());
            // Degenerate: no relative spread, or only round-off (< 1e-9 in the plotted units,
            // e.g. a deviator of 1e-10 kPa on an isotropic path).
            if span <= (1e-12 * mag).max(1e-9) {
                let mid = 0.5 * (lo + hi);
                let d = if mag < 1e-9 { 1.0 } else { 0.1 * mag };
                (mid - d, mid + d)
            } else {
                (lo - 0.05 * span, hi + 0.05 * span)
            }
        };
        let (x0, x1) = pad(b[0], b[1]);
        let (y0, y1) = pad(b[2], b[3]);
        (x0, x1, y0, y1)
    }
}

/// A figure: a title and panels laid out row by row in `columns` columns.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// Title across the top.
    pub title: String,
    /// Panels, row-major.
    pub panels: Vec<Panel>,
    /// Number of columns of the grid (≥ 1).
    pub columns: usize,
    /// Size of one panel in pixels (width, height).
    pub panel_size: (u32, u32),
}

impl Figure {
    /// An empty figure with 2 columns of 640×480 panels.
    pub fn new(title: impl Into<String>) -> Self {
        Figure {
            title: title.into(),
            panels: Vec::new(),
            columns: 2,
            panel_size: (640, 480),
        }
    }

    /// Adds a panel (builder style).
    pub fn with(mut self, panel: Panel) -> Self {
        self.panels.push(panel);
        self
    }

    /// Adds a panel.
    pub fn push(&mut self, panel: Panel) {
        self.panels.push(panel);
    }

    /// Sets the number of columns (builder style).
    pub fn columns(mut self, columns: usize) -> Self {
        self.columns = columns.max(1);
        self
    }

    /// Renders the figure into a PNG file.
    ///
    /// The PNG is drawn into a temporary file `.<stem>.partial-<pid>.png` beside `path` and
    /// renamed over it once complete, so a failed write (a full disk) never leaves a truncated
    /// figure; the temporary file is removed on failure.
    pub fn save_png(&self, path: &Path) -> Result<(), PlotError> {
        ensure_font()?;
        let temp = temporary_png(path);
        let drawn = self
            .draw_png(&temp)
            .and_then(|()| std::fs::rename(&temp, path).map_err(|e| e.to_string()));
        drawn.map_err(|message| {
            let _ = std::fs::remove_file(&temp);
            PlotError::Draw {
                path: path.to_path_buf(),
                message,
            }
        })
    }

    /// Renders the figure into the PNG file `path`; the error in words.
    fn draw_png(&self, path: &Path) -> Result<(), String> {
        let draw_err = |e: &dyn std::fmt::Display| readable_draw_error(&e.to_string());
        let cols = self.columns.clamp(1, self.panels.len().max(1));
        let rows = self.panels.len().div_ceil(cols).max(1);
        let (w, h) = self.panel_size;
        let title_h = 40;
        let size = (w * cols as u32, h * rows as u32 + title_h);
        let root = BitMapBackend::new(path, size).into_drawing_area();
        root.fill(&WHITE).map_err(|e| draw_err(&e))?;
        let (top, body) = root.split_vertically(title_h);
        top.draw_text(
            &self.title,
            &TextStyle::from((FAMILY, 24).into_font()).color(&BLACK),
            (10, 8),
        )
        .map_err(|e| draw_err(&e))?;
        let areas = body.split_evenly((rows, cols));
        for (panel, area) in self.panels.iter().zip(areas.iter()) {
            draw_panel(panel, area).map_err(|e| draw_err(&e))?;
        }
        root.present().map_err(|e| draw_err(&e))
    }
}

/// The temporary file of [`Figure::save_png`] for `path`: `.<stem>.partial-<pid>.png` (the
/// encoder picks the format from the extension).
fn temporary_png(path: &Path) -> PathBuf {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{stem}.partial-{}.png", std::process::id()))
}

/// The plotters/image error text `message` in words: the operating system's reason (e.g. "No
/// space left on device") where it holds one, else the text as it is.
fn readable_draw_error(message: &str) -> String {
    const REASONS: [&str; 4] = [
        "No space left on device",
        "Disk quota exceeded",
        "Permission denied",
        "Read-only file system",
    ];
    match REASONS.iter().find(|r| message.contains(*r)) {
        Some(reason) => reason.to_string(),
        None => message.to_string(),
    }
}

/// Colours of successive series.
const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
];

/// Compact tick label: fixed notation for moderate magnitudes, scientific otherwise.
fn tick(v: &f64) -> String {
    let a = v.abs();
    // Round-off around zero (e.g. -1.1e-16 at the end of a flat axis) is printed as 0.
    if a < 1e-9 {
        "0".to_string()
    } else if !(1e-3..1e5).contains(&a) {
        format!("{v:.2e}")
    } else {
        let s = format!("{v:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    }
}

fn draw_panel<DB: DrawingBackend>(
    panel: &Panel,
    area: &DrawingArea<DB, plotters::coord::Shift>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (x0, x1, y0, y1) = panel.bounds();
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, (FAMILY, 18))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(75)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    chart
        .configure_mesh()
        .x_desc(panel.x_label.as_str())
        .y_desc(panel.y_label.as_str())
        .x_label_formatter(&tick)
        .y_label_formatter(&tick)
        .label_style((FAMILY, 13))
        .axis_desc_style((FAMILY, 15))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()?;
    let mut any_label = false;
    for (i, s) in panel.series.iter().enumerate() {
        let color = PALETTE[i % PALETTE.len()];
        let pts: Vec<(f64, f64)> = s
            .points
            .iter()
            .copied()
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .collect();
        let anno = match s.style {
            // one path per segment: a thick polyline's miter joins draw a sharp reversal
            // (a one-step spike of a time history) as a long needle out of the panel
            SeriesStyle::Line => chart.draw_series(
                pts.windows(2)
                    .map(|ab| PathElement::new(vec![ab[0], ab[1]], color.stroke_width(2))),
            )?,
            SeriesStyle::Markers => {
                chart.draw_series(pts.into_iter().map(|p| Circle::new(p, 3, color.filled())))?
            }
            SeriesStyle::Segments => chart.draw_series(
                s.points
                    .chunks_exact(2)
                    .filter(|ab| ab.iter().all(|(x, y)| x.is_finite() && y.is_finite()))
                    .map(|ab| PathElement::new(vec![ab[0], ab[1]], color.stroke_width(1))),
            )?,
        };
        if !s.label.is_empty() {
            any_label = true;
            anno.label(s.label.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2)));
        }
    }
    if any_label {
        chart
            .configure_series_labels()
            .position(match panel.legend_lower_right {
                true => SeriesLabelPosition::LowerRight,
                false => SeriesLabelPosition::UpperLeft,
            })
            .label_font((FAMILY, 13))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()?;
    }
    Ok(())
}

/// Loads and registers the TrueType font once per process (see the module docs).
pub fn ensure_font() -> Result<(), PlotError> {
    static FONT: OnceLock<Result<(), String>> = OnceLock::new();
    FONT.get_or_init(load_font).clone().map_err(PlotError::Font)
}

fn load_font() -> Result<(), String> {
    let candidates: Vec<PathBuf> = match std::env::var_os(FONT_ENV) {
        Some(p) => vec![PathBuf::from(p)],
        None => FONT_PATHS.iter().map(PathBuf::from).collect(),
    };
    let (path, bytes) = read_font(&candidates)?;
    let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
    plotters::style::register_font(FAMILY, FontStyle::Normal, bytes)
        .map_err(|_| format!("{}: not a usable TrueType font", path.display()))
}

/// The first readable file of `candidates`, or an error that says how to get a font.
fn read_font(candidates: &[PathBuf]) -> Result<(PathBuf, Vec<u8>), String> {
    candidates
        .iter()
        .find_map(|p| std::fs::read(p).ok().map(|b| (p.clone(), b)))
        .ok_or_else(|| {
            format!(
                "none of {candidates:?} could be read; install fonts-dejavu-core (Debian/Ubuntu) or set \
                 {FONT_ENV}=/path/to/font.ttf"
            )
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A time history with a one-step spike (the crest acceleration of a quake: 23, −172,
    /// 78 m/s² on three steps) stays inside its panel: the rows of the panel's top margin,
    /// above the plotting area, stay white. A thick polyline's miter join at the spike's sharp
    /// reversals drew a needle through them.
    #[test]
    fn a_one_step_spike_stays_inside_its_panel() {
        ensure_font().unwrap();
        // 20 s at 0.01 s: a quarter of a pixel per step, so the reversals are nearly
        // hairpins
        let spike = [23.1, -172.3, 77.6];
        let points: Vec<(f64, f64)> = (0..2001)
            .map(|i| {
                let a = match i {
                    1210..=1212 => spike[i - 1210],
                    _ => 3.0 * (i as f64 * 0.37).sin(),
                };
                (i as f64 * 0.01, a)
            })
            .collect();
        let panel = Panel::new("", "t (s)", "a (m/s2)").with(Series::line("crest", points));
        let (w, h) = (640u32, 480u32);
        let mut buffer = vec![0u8; (w * h * 3) as usize];
        {
            let root = BitMapBackend::with_buffer(&mut buffer, (w, h)).into_drawing_area();
            root.fill(&WHITE).unwrap();
            draw_panel(&panel, &root).unwrap();
            root.present().unwrap();
        }
        // the chart's margin is 12 px: nothing but background above it
        let inked = buffer[..(10 * w * 3) as usize]
            .iter()
            .filter(|&&v| v != 255)
            .count();
        assert_eq!(inked, 0, "{inked} coloured bytes in the top 10 rows");
    }

    #[test]
    fn writes_a_multi_panel_png() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("fig.png");
        let a = Panel::new("Sine", "x (-)", "y (-)")
            .with(Series::line(
                "sin",
                (0..100)
                    .map(|i| (i as f64 * 0.1, (i as f64 * 0.1).sin()))
                    .collect(),
            ))
            .with(Series::markers(
                "pts",
                vec![(0.0, 0.0), (5.0, 0.5), (f64::NAN, 1.0)],
            ));
        let b = Panel::new("Constant", "x", "y").with(Series::line("", vec![(1.0, 2.0), (1.0, 2.0)]));
        let empty = Panel::new("Empty", "x", "y");
        Figure::new("Test figure")
            .with(a)
            .with(b)
            .with(empty)
            .save_png(&path)
            .unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert!(
            bytes.len() > 5000 && bytes.starts_with(b"\x89PNG"),
            "{} bytes",
            bytes.len()
        );
    }

    #[test]
    fn missing_font_says_what_to_install() {
        let err = read_font(&[PathBuf::from("/nonexistent/font.ttf")]).unwrap_err();
        assert!(
            err.contains("fonts-dejavu-core")
                && err.contains(FONT_ENV)
                && err.contains("/nonexistent/font.ttf"),
            "{err}"
        );
    }

    /// Flat and round-off-only series get a drawable axis around their value.
    #[test]
    fn degenerate_ranges_are_widened() {
        let flat = Panel::new("t", "x", "y").with(Series::line("", vec![(0.0, 5.0), (1.0, 5.0)]));
        let (x0, x1, y0, y1) = flat.bounds();
        assert!((x0 + 0.05).abs() < 1e-12 && (x1 - 1.05).abs() < 1e-12);
        assert!((y0 - 4.5).abs() < 1e-12 && (y1 - 5.5).abs() < 1e-12, "{y0} {y1}");
        let noise = Panel::new("t", "x", "y").with(Series::line("", vec![(0.0, 1e-13), (1.0, -2e-12)]));
        let (_, _, y0, y1) = noise.bounds();
        assert!((y0 + 1.0).abs() < 1e-9 && (y1 - 1.0).abs() < 1e-9, "{y0} {y1}");
    }

    #[test]
    fn tick_labels_are_compact() {
        assert_eq!(tick(&0.0), "0");
        assert_eq!(tick(&-1.11e-16), "0");
        assert_eq!(tick(&12.5), "12.5");
        assert_eq!(tick(&2.0e6), "2.00e6");
        assert_eq!(tick(&-0.25), "-0.25");
    }
}
