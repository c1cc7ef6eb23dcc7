//! Deterministic SVG figures.
//!
//! Text is laid out with the DejaVu Sans font bundled in `assets/fonts/` and registered from
//! bytes (plotters' `ab_glyph` feature), never with the machine's fonts, and plotters maps
//! every coordinate to whole pixels: the same data give the same bytes on every machine.
//! A figure is a grid of [`Panel`]s, each a set of [`Series`] on linear axes.

use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::sync::Once;
use thiserror::Error;

/// Font family every text element uses (the bundled DejaVu Sans).
pub const FONT: &str = "sans-serif";
static FONT_BYTES: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
static REGISTER: Once = Once::new();

#[derive(Debug, Error)]
#[error("drawing failed: {0}")]
pub struct PlotError(String);

fn err<E: std::fmt::Debug>(e: E) -> PlotError {
    PlotError(format!("{e:?}"))
}

fn ensure_font() {
    REGISTER.call_once(|| {
        plotters::style::register_font(FONT, FontStyle::Normal, FONT_BYTES).unwrap_or_else(|_| {
            panic!("the bundled font assets/fonts/DejaVuSans.ttf is not a valid font")
        });
    });
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Style {
    /// A polyline of `width` pixels, dashed or solid.
    Line { width: u32, dashed: bool },
    /// One circle of radius `size` pixels per point.
    Markers { size: u32, filled: bool },
    /// A shaded area between `points` (lower edge) and `upper`.
    Band,
}

/// One data series of a panel.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend entry; `None` keeps it out of the legend.
    pub label: Option<String>,
    pub color: RGBColor,
    pub style: Style,
    pub points: Vec<(f64, f64)>,
    /// Upper edge of a [`Style::Band`] (same x values as `points`); empty otherwise.
    pub upper: Vec<(f64, f64)>,
}

impl Series {
    fn new(label: Option<String>, color: RGBColor, style: Style, points: Vec<(f64, f64)>) -> Self {
        Self {
            label,
            color,
            style,
            points,
            upper: vec![],
        }
    }
    pub fn line(
        label: Option<String>,
        color: RGBColor,
        width: u32,
        points: Vec<(f64, f64)>,
    ) -> Self {
        Self::new(
            label,
            color,
            Style::Line {
                width,
                dashed: false,
            },
            points,
        )
    }
    pub fn dashed(
        label: Option<String>,
        color: RGBColor,
        width: u32,
        points: Vec<(f64, f64)>,
    ) -> Self {
        Self::new(
            label,
            color,
            Style::Line {
                width,
                dashed: true,
            },
            points,
        )
    }
    pub fn markers(
        label: Option<String>,
        color: RGBColor,
        size: u32,
        points: Vec<(f64, f64)>,
    ) -> Self {
        Self::new(
            label,
            color,
            Style::Markers {
                size,
                filled: false,
            },
            points,
        )
    }
    pub fn band(
        label: Option<String>,
        color: RGBColor,
        lower: Vec<(f64, f64)>,
        upper: Vec<(f64, f64)>,
    ) -> Self {
        Self {
            upper,
            ..Self::new(label, color, Style::Band, lower)
        }
    }
}

/// Where a panel's legend goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LegendPosition {
    UpperLeft,
    UpperRight,
    LowerLeft,
    LowerRight,
}

impl LegendPosition {
    fn to_plotters(self) -> SeriesLabelPosition {
        match self {
            LegendPosition::UpperLeft => SeriesLabelPosition::UpperLeft,
            LegendPosition::UpperRight => SeriesLabelPosition::UpperRight,
            LegendPosition::LowerLeft => SeriesLabelPosition::LowerLeft,
            LegendPosition::LowerRight => SeriesLabelPosition::LowerRight,
        }
    }
}

/// One chart: axes, series, notes written inside the plotting area.
#[derive(Debug, Clone)]
pub struct Panel {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub x_range: (f64, f64),
    pub y_range: (f64, f64),
    pub series: Vec<Series>,
    /// Lines of text drawn in the lower right corner inside the plotting area.
    pub notes: Vec<String>,
    pub legend: Option<LegendPosition>,
    /// Whether the x and y axes are logarithmic (base 10). Points and ranges stay in data units
    /// (every value on a log axis must be positive); ticks are labelled in data units.
    pub log_scale: (bool, bool),
}

impl Panel {
    /// A panel of the mean pressure p̄/E* (linear axes, legend upper left) against `x_label`
    /// over `x_range`, its y range padded around every series' points.
    pub fn mean_pressure(
        title: String,
        x_label: &str,
        x_range: (f64, f64),
        series: Vec<Series>,
        notes: Vec<String>,
    ) -> Panel {
        let y_range = padded_range(series.iter().flat_map(|s| s.points.iter().map(|p| p.1)));
        Panel {
            title,
            x_label: x_label.into(),
            y_label: "p̄/E*".into(),
            x_range,
            y_range,
            series,
            notes,
            log_scale: (false, false),
            legend: Some(LegendPosition::UpperLeft),
        }
    }
}

/// A figure: a caption, a `rows × cols` grid of panels (row-major) and footer lines.
#[derive(Debug, Clone)]
pub struct Figure {
    pub width: u32,
    pub height: u32,
    pub caption: String,
    pub grid: (usize, usize),
    pub panels: Vec<Panel>,
    /// Lines of text under the panels (provenance, missing data, extrapolation warnings).
    pub footer: Vec<String>,
    /// Font size of titles, labels and notes, px.
    pub font_px: u32,
}

/// Colours used across figures, chosen to stay distinct for colour-blind readers (Okabe–Ito).
pub mod palette {
    use plotters::style::RGBColor;
    pub const BLACK: RGBColor = RGBColor(0, 0, 0);
    pub const GREY: RGBColor = RGBColor(110, 110, 110);
    pub const VERMILION: RGBColor = RGBColor(213, 94, 0);
    pub const BLUE: RGBColor = RGBColor(0, 114, 178);
    pub const GREEN: RGBColor = RGBColor(0, 158, 115);
    pub const ORANGE: RGBColor = RGBColor(230, 159, 0);
    pub const SKY: RGBColor = RGBColor(86, 180, 233);
    pub const PURPLE: RGBColor = RGBColor(204, 121, 167);
    pub const YELLOW: RGBColor = RGBColor(240, 228, 66);
    /// A cycle for families of lines.
    pub const CYCLE: [RGBColor; 7] = [BLUE, VERMILION, GREEN, ORANGE, SKY, PURPLE, BLACK];
}

/// Lower and upper plot limits that enclose `values` with a 5% margin (0 kept as a floor
/// when every value is non-negative).
pub fn padded_range(values: impl IntoIterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .into_iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let span = (hi - lo).max(1e-12 * hi.abs().max(1.0));
    let lo = if lo >= 0.0 && lo - 0.05 * span < 0.0 {
        0.0
    } else {
        lo - 0.05 * span
    };
    (lo, hi + 0.05 * span)
}

/// Renders `figure` to SVG text.
pub fn render_svg(figure: &Figure) -> Result<String, PlotError> {
    ensure_font();
    let mut svg = String::new();
    {
        let root =
            SVGBackend::with_string(&mut svg, (figure.width, figure.height)).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        let fs = figure.font_px;
        let root = root
            .titled(&figure.caption, (FONT, fs + 6).into_font())
            .map_err(err)?;
        let footer_h = if figure.footer.is_empty() {
            0
        } else {
            (fs + 6) * figure.footer.len() as u32 + 10
        };
        let (body, footer) = root.split_vertically(root.dim_in_pixel().1 - footer_h);
        for (area, panel) in body.split_evenly(figure.grid).iter().zip(&figure.panels) {
            draw_panel(area, panel, fs)?;
        }
        for (i, line) in figure.footer.iter().enumerate() {
            footer
                .draw_text(
                    line,
                    &(FONT, fs).into_font().color(&BLACK),
                    (12, 4 + i as i32 * (fs as i32 + 6)),
                )
                .map_err(err)?;
        }
        root.present().map_err(err)?;
    }
    Ok(svg)
}

/// Tick labels of an axis: six on a linear axis; on a logarithmic one (range in log₁₀) one per
/// decade, so that every tick is a power of ten.
fn label_count(log: bool, range: (f64, f64)) -> usize {
    if log {
        ((range.1 - range.0).round() as usize + 1).max(2)
    } else {
        6
    }
}

/// The panel with log₁₀ of every value on a logarithmic axis (plotters draws it on a linear
/// axis whose ticks [`draw_panel`] labels in data units); an error names a value that has no
/// logarithm.
fn to_log_coordinates(panel: &Panel) -> Result<Panel, PlotError> {
    let (log_x, log_y) = panel.log_scale;
    let log = |on: bool, v: f64, axis: &str| -> Result<f64, PlotError> {
        if !on {
            Ok(v)
        } else if v > 0.0 && v.is_finite() {
            Ok(v.log10())
        } else {
            Err(PlotError(format!(
                "panel `{}`: {axis} value {v} on a logarithmic axis",
                panel.title
            )))
        }
    };
    let point = |&(x, y): &(f64, f64)| Ok((log(log_x, x, "x")?, log(log_y, y, "y")?));
    let mut out = panel.clone();
    out.x_range = (
        log(log_x, panel.x_range.0, "x")?,
        log(log_x, panel.x_range.1, "x")?,
    );
    out.y_range = (
        log(log_y, panel.y_range.0, "y")?,
        log(log_y, panel.y_range.1, "y")?,
    );
    for s in &mut out.series {
        s.points = s.points.iter().map(point).collect::<Result<_, _>>()?;
        s.upper = s.upper.iter().map(point).collect::<Result<_, _>>()?;
    }
    Ok(out)
}

/// A tick label: at most four significant digits, no trailing zeros, never `-0`.
/// Tick label: four significant digits; a tick at round-off distance from zero (plotters
/// places ticks by adding steps, so the zero tick can come out as −1.1e-16) reads 0.
fn tick(v: f64) -> String {
    if v.abs() < 1e-12 {
        "0".into()
    } else {
        crate::numfmt::sig_digits(v, 4)
    }
}

/// The chart type every panel is drawn on: linear f64 axes (log₁₀ values on a log axis).
type PanelChart<'a, 'b> =
    ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Draws `panel` in `area`: axes and mesh, every series, the legend, then the notes.
fn draw_panel(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    panel: &Panel,
    fs: u32,
) -> Result<(), PlotError> {
    let panel = &to_log_coordinates(panel)?;
    let mut chart = draw_axes(area, panel, fs)?;
    for s in &panel.series {
        draw_series(&mut chart, s)?;
    }
    if let Some(pos) = panel.legend {
        chart
            .configure_series_labels()
            .position(pos.to_plotters())
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(160, 160, 160))
            .label_font((FONT, fs - 2).into_font())
            .draw()
            .map_err(err)?;
    }
    draw_notes(&chart, panel, fs)
}

/// Builds the chart of `panel` (already in log coordinates on a log axis) in `area`, with its
/// caption, and draws the mesh, the axis descriptions and the tick labels in data units.
fn draw_axes<'a, 'b>(
    area: &'a DrawingArea<SVGBackend<'b>, Shift>,
    panel: &Panel,
    fs: u32,
) -> Result<PanelChart<'a, 'b>, PlotError> {
    let (log_x, log_y) = panel.log_scale;
    let x_tick = move |v: &f64| tick(if log_x { 10f64.powf(*v) } else { *v });
    let y_tick = move |v: &f64| tick(if log_y { 10f64.powf(*v) } else { *v });
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, (FONT, fs + 2).into_font())
        .margin(8)
        .margin_right(24)
        .x_label_area_size(fs * 2 + 14)
        .y_label_area_size(fs * 3 + 22)
        .build_cartesian_2d(
            panel.x_range.0..panel.x_range.1,
            panel.y_range.0..panel.y_range.1,
        )
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc(&panel.x_label)
        .y_desc(&panel.y_label)
        .label_style((FONT, fs - 2).into_font())
        .axis_desc_style((FONT, fs).into_font())
        .light_line_style(RGBColor(235, 235, 235))
        .bold_line_style(RGBColor(215, 215, 215))
        .x_labels(label_count(log_x, panel.x_range))
        .y_labels(label_count(log_y, panel.y_range))
        .x_label_formatter(&x_tick)
        .y_label_formatter(&y_tick)
        .draw()
        .map_err(err)?;
    Ok(chart)
}

/// Draws one series in its style (band, solid or dashed line, markers) and, if it has a label,
/// registers its legend entry with the matching glyph ([`legend_glyph`]).
fn draw_series<'a, 'b: 'a>(chart: &mut PanelChart<'a, 'b>, s: &Series) -> Result<(), PlotError> {
    let color = s.color;
    let anno = match s.style {
        Style::Band => {
            let mut outline = s.points.clone();
            outline.extend(s.upper.iter().rev().copied());
            chart
                .draw_series(std::iter::once(Polygon::new(
                    outline,
                    color.mix(0.22).filled(),
                )))
                .map_err(err)?
        }
        Style::Line {
            width,
            dashed: false,
        } => chart
            .draw_series(LineSeries::new(
                s.points.iter().copied(),
                color.stroke_width(width),
            ))
            .map_err(err)?,
        Style::Line {
            width,
            dashed: true,
        } => chart
            .draw_series(DashedLineSeries::new(
                s.points.iter().copied(),
                8,
                5,
                color.stroke_width(width),
            ))
            .map_err(err)?,
        Style::Markers { size, filled } => {
            let style = if filled {
                color.filled()
            } else {
                color.stroke_width(2)
            };
            chart
                .draw_series(s.points.iter().map(|&p| Circle::new(p, size, style)))
                .map_err(err)?
        }
    };
    if let Some(label) = &s.label {
        let style = s.style;
        anno.label(label)
            .legend(move |(x, y)| legend_glyph(style, color, (x, y)));
    }
    Ok(())
}

/// The legend glyph of a series of `style` and `color` at legend position `(x, y)`: a circle
/// for markers, a shaded box for a band, a short line otherwise.
fn legend_glyph<'b>(
    style: Style,
    color: RGBColor,
    (x, y): (i32, i32),
) -> DynElement<'static, SVGBackend<'b>, (i32, i32)> {
    match style {
        Style::Markers { size, .. } => {
            Circle::new((x + 10, y), size, color.stroke_width(2)).into_dyn()
        }
        Style::Band => {
            Rectangle::new([(x, y - 5), (x + 20, y + 5)], color.mix(0.22).filled()).into_dyn()
        }
        Style::Line { width, .. } => {
            PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(width)).into_dyn()
        }
    }
}

/// Writes the panel's notes right-aligned in the lower right corner of the plotting area, the
/// last note lowest, where the curves (rising from the origin) leave room.
fn draw_notes(chart: &PanelChart<'_, '_>, panel: &Panel, fs: u32) -> Result<(), PlotError> {
    let plot = chart.plotting_area();
    let (px, py) = plot.get_base_pixel();
    let corner = plot.map_coordinate(&(panel.x_range.1, panel.y_range.0));
    let style = (FONT, fs - 1)
        .into_font()
        .color(&BLACK)
        .pos(Pos::new(HPos::Right, VPos::Bottom));
    let n = panel.notes.len() as i32;
    for (i, note) in panel.notes.iter().enumerate() {
        let line_from_bottom = n - 1 - i as i32;
        let pos = (
            corner.0 - 8 - px,
            corner.1 - 6 - line_from_bottom * (fs as i32 + 3) - py,
        );
        plot.strip_coord_spec()
            .draw_text(note, &style, pos)
            .map_err(err)?;
    }
    Ok(())
}
