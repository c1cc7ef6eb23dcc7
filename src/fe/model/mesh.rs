//! Quad mesh of the half-wavelength layer, graded toward the contact face and toward the
//! indenter's peak, its columns optionally coarsened with depth.
//!
//! Domain (units of λ): `X ∈ [0, ½]`, `Y ∈ [0, h]`; the contact face is `Y = 0`, the
//! bonded face `Y = h`. Without coarsening the mesh is structured: node `(i, j)` (column
//! `i ∈ 0..=nx`, row `j ∈ 0..=ny`) has id `j (nx+1) + i`. Quads are counter-clockwise.
//!
//! Grading:
//! * along `X`: `X = ½ (ξ + β ξ²)/(1 + β)` with `ξ` uniform, so the spacing at `X = ½`
//!   is `peak_ratio = 1 + 2β` times the spacing at the peak `X = 0`. Under the peak the
//!   surface stretches strongly at large aspect ratio (≈ 3.7× at AR = 0.3, R10), so the
//!   reference mesh is refined there to keep the current spacing near uniform. The
//!   default ratio 4 makes the surface elements under the peak taller than wide in the
//!   reference configuration, so that they are not much flatter than square when
//!   stretched. With smaller ratios the coarse mesh loses stability under the peak at
//!   AR = 0.3 before a/λ = 0.45 (Newton stalls on an indefinite tangent whose direction is
//!   the sliding node next to the peak; docs/replication.md R10);
//! * along `Y`: geometric layers whose first (bottom) layer is
//!   `first_layer_over_dx × (½/nx)` thick, growing toward the bonded face.
//!
//! Coarsening ([`Grading::coarsen_at_aspect`]): in a row whose height reaches that many times
//! the mean width of its columns, a transition row joins every three columns into one with a
//! conforming four-quad template (no hanging nodes), so that the deep elements are not tall
//! slivers: the fields the small waves of a profile raise die out within a small wavelength of
//! the face, and below that one column in three resolves the big wave's (docs/replication.md
//! R13, "Columns coarsened with depth").

/// Mesh resolution. Each named level has [`MeshLevel::REFINEMENT_RATIO`] times the
/// element counts of the previous one (the three levels of the convergence study).
///
/// The default was chosen as the coarsest of these whose three-level Richardson estimate
/// met the 0.5 % accuracy target of `p̄(a)` over a/λ ∈ [0.1, 0.45]. Its error as the
/// speed–accuracy scene measures it is in `figures/speed_accuracy_bands.csv`
/// (docs/results.md, speed and accuracy); a user who needs less picks a finer mesh by
/// tolerance. The coarser 24 × 12 mesh does not reach a/λ = 0.45 at AR = 0.3.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum MeshLevel {
    /// 32 × 16 elements.
    Coarse,
    /// 48 × 24 elements.
    #[default]
    Default,
    /// 72 × 36 elements.
    Fine,
    /// Explicit counts along the contact face (`nx`) and the thickness (`ny`).
    Elements {
        /// Elements along `X ∈ [0, ½]`.
        nx: usize,
        /// Elements across the thickness.
        ny: usize,
    },
}

impl MeshLevel {
    /// The mesh of `nx` elements along the contact face and half as many (at least 2) across
    /// the thickness: what `wavy solve --mesh N` and a spec's `mesh = "N"` mean.
    pub fn along_face(nx: usize) -> Self {
        MeshLevel::Elements {
            nx,
            ny: (nx / 2).max(2),
        }
    }

    /// Ratio of the element counts of consecutive named levels.
    pub const REFINEMENT_RATIO: f64 = 1.5;

    /// Element counts `(nx, ny)`.
    pub fn counts(self) -> (usize, usize) {
        match self {
            MeshLevel::Coarse => (32, 16),
            MeshLevel::Default => (48, 24),
            MeshLevel::Fine => (72, 36),
            MeshLevel::Elements { nx, ny } => (nx, ny),
        }
    }

    /// Displacement unknowns of the mesh, two per node (before the boundary and contact
    /// constraints): the size that cost tables report.
    pub fn unknowns(self) -> usize {
        let (nx, ny) = self.counts();
        2 * (nx + 1) * (ny + 1)
    }

    /// [`Self::unknowns`] of the mesh as `grading` builds it on a layer `thickness` thick: fewer
    /// where it coarsens the columns with depth.
    pub fn unknowns_graded(self, grading: Grading, thickness: f64) -> usize {
        if grading.coarsen_at_aspect == 0.0 {
            return self.unknowns();
        }
        let (nx, ny) = self.counts();
        2 * Mesh::graded(nx, ny, thickness, grading).nodes.len()
    }
}

/// A mesh resolution that is not one of the names or an element count in range.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("value {value} is out of range; allowed: {}", MeshLevel::ALLOWED)]
pub struct MeshLevelParseError {
    /// The text that was given.
    pub value: String,
}

impl MeshLevel {
    /// Element counts along the face accepted by [`MeshLevel::from_str`].
    pub const ELEMENTS_ALONG_FACE: std::ops::RangeInclusive<usize> = 4..=2048;

    /// What [`MeshLevel::from_str`] accepts, in words.
    pub const ALLOWED: &'static str = "coarse (32×16), default (48×24), fine (72×36), or N elements along the face (4 to 2048; N/2 across the thickness)";
}

impl std::str::FromStr for MeshLevel {
    type Err = MeshLevelParseError;
    /// `coarse`, `default`, `fine`, or `N` elements along the face (`N/2`, at least 2,
    /// across the thickness).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "coarse" => Ok(MeshLevel::Coarse),
            "default" => Ok(MeshLevel::Default),
            "fine" => Ok(MeshLevel::Fine),
            n => match n.parse::<usize>() {
                Ok(nx) if Self::ELEMENTS_ALONG_FACE.contains(&nx) => Ok(Self::along_face(nx)),
                _ => Err(MeshLevelParseError { value: s.into() }),
            },
        }
    }
}

/// The name [`MeshLevel::from_str`] reads back (`coarse`, `default`, `fine`, `N`), or `N×M` for
/// counts that no name gives.
impl std::fmt::Display for MeshLevel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            MeshLevel::Coarse => f.write_str("coarse"),
            MeshLevel::Default => f.write_str("default"),
            MeshLevel::Fine => f.write_str("fine"),
            MeshLevel::Elements { nx, ny } if Self::along_face(nx).counts().1 == ny => {
                write!(f, "{nx}")
            }
            MeshLevel::Elements { nx, ny } => write!(f, "{nx}×{ny}"),
        }
    }
}

/// Grading parameters.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Grading {
    /// Spacing ratio along the contact face: `ΔX(½) / ΔX(0)` (≥ 1); a single sinusoid steeper
    /// than AR 0.3 is meshed with more under finite kinematics ([`Grading::for_sinusoid`]).
    pub peak_ratio: f64,
    /// Bottom layer thickness in units of the mean face spacing `½/nx`.
    pub first_layer_over_dx: f64,
    /// Coarsen the columns threefold in a row whose height reaches this many times the mean
    /// column width (a conforming transition row); 0 keeps every column to the bonded face.
    pub coarsen_at_aspect: f64,
}

/// The steepest sinusoid whose peak the grading's own `peak_ratio` serves: the paper's range,
/// AR 0.3 (docs/replication.md R10).
pub const STEEP_PEAK_FROM_ASPECT_RATIO: f64 = 0.3;

/// How fast the surface stretch under the peak grows with the aspect ratio beyond
/// [`STEEP_PEAK_FROM_ASPECT_RATIO`]: `d ln s / d AR`, `s` the stretch of the face element at the
/// peak at a/λ 0.45, measured 2.85 at AR 0.3 and 5.12 at AR 0.4 on 96 face elements (3.74 at
/// AR 0.35, where this rate predicts 3.82; docs/replication.md R10).
pub const PEAK_STRETCH_LOG_RATE_PER_ASPECT_RATIO: f64 = 5.86;

impl Grading {
    /// Uniform spacing along the contact face (`peak_ratio` 1), the default layers: the mesh of
    /// a profile whose small waves touch anywhere on the face.
    pub fn uniform_face() -> Self {
        Self {
            peak_ratio: 1.0,
            ..Self::default()
        }
    }

    /// The grading of a single sinusoid of aspect ratio `aspect_ratio`. Beyond
    /// [`STEEP_PEAK_FROM_ASPECT_RATIO`] the peak's element, stretched `s` times along the face
    /// and as much thinned across it, ends `s²` times flatter than its reference shape, and the
    /// coarse layer loses stability there (docs/replication.md R10); so `1 + peak_ratio`, to
    /// which the peak element's height over width is proportional, grows as `s²`
    /// ([`PEAK_STRETCH_LOG_RATE_PER_ASPECT_RATIO`]) and the stretched element keeps the shape it
    /// has at AR 0.3 (the default 4 becomes 8.0 at AR 0.35 and 15.1 at AR 0.4).
    pub fn for_sinusoid(self, aspect_ratio: f64) -> Self {
        let excess = aspect_ratio - STEEP_PEAK_FROM_ASPECT_RATIO;
        if excess <= 0.0 {
            return self;
        }
        let stretch_growth_squared = (2.0 * PEAK_STRETCH_LOG_RATE_PER_ASPECT_RATIO * excess).exp();
        Self {
            peak_ratio: (1.0 + self.peak_ratio) * stretch_growth_squared - 1.0,
            ..self
        }
    }
}

impl Default for Grading {
    fn default() -> Self {
        Self {
            peak_ratio: 4.0,
            first_layer_over_dx: 1.0,
            coarsen_at_aspect: 0.0,
        }
    }
}

/// Quad mesh of the layer: structured rows of columns, the columns coarsened threefold where
/// the rows have grown taller than [`Grading::coarsen_at_aspect`] times their width.
#[derive(Clone, Debug)]
pub struct Mesh {
    /// Elements along `X` on the contact face.
    pub nx: usize,
    /// Rows of elements along `Y`.
    pub ny: usize,
    /// Layer thickness `h/λ`.
    pub thickness: f64,
    /// Reference node coordinates.
    pub nodes: Vec<[f64; 2]>,
    /// Quads (node ids, counter-clockwise).
    pub quads: Vec<[usize; 4]>,
    /// Contact-face nodes in order of increasing `X`.
    pub bottom: Vec<usize>,
    /// The node above each contact-face node, at the top of the first row of elements (same
    /// order as `bottom`).
    pub above_bottom: Vec<usize>,
    /// Bonded-face nodes in order of increasing `X`.
    pub top: Vec<usize>,
    /// Nodes on the lateral faces `X = 0` and `X = ½`, each from the contact face up.
    pub sides: [Vec<usize>; 2],
}

impl Mesh {
    /// Build the graded mesh: the face spacing graded toward the peak, the rows toward the
    /// contact face, and the columns coarsened with depth if `grading.coarsen_at_aspect > 0`.
    pub fn graded(nx: usize, ny: usize, thickness: f64, grading: Grading) -> Self {
        let beta = ((grading.peak_ratio - 1.0) / 2.0).max(0.0);
        let xs: Vec<f64> = (0..=nx)
            .map(|i| {
                let xi = i as f64 / nx as f64;
                0.5 * (xi + beta * xi * xi) / (1.0 + beta)
            })
            .collect();
        let ys = geometric_layers(ny, thickness, grading.first_layer_over_dx * 0.5 / nx as f64);
        let mut mesh = Self {
            nx,
            ny,
            thickness,
            nodes: Vec::new(),
            quads: Vec::new(),
            bottom: Vec::new(),
            above_bottom: Vec::new(),
            top: Vec::new(),
            sides: [Vec::new(), Vec::new()],
        };
        let mut line: Vec<usize> = xs.iter().map(|&x| mesh.add_node([x, 0.0])).collect();
        mesh.bottom = line.clone();
        mesh.add_side_nodes(&line);
        for (j, rows) in ys.windows(2).enumerate() {
            let (y0, y1) = (rows[0], rows[1]);
            let columns = line.len() - 1;
            let width = mesh.line_width(&line) / columns as f64;
            let coarsen = j >= 1
                && columns >= TRANSITION_COLUMNS
                && grading.coarsen_at_aspect > 0.0
                && y1 - y0 >= grading.coarsen_at_aspect * width;
            line = match coarsen {
                true => mesh.transition_row(&line, y0, y1),
                false => mesh.plain_row(&line, y1),
            };
            mesh.add_side_nodes(&line);
            if j == 0 {
                mesh.above_bottom = line.clone();
            }
        }
        mesh.top = line;
        mesh
    }

    /// The extent in `X` of a line of nodes (the layer's width, ½).
    fn line_width(&self, line: &[usize]) -> f64 {
        let last = *line.last().expect("a line has nodes");
        self.nodes[last][0] - self.nodes[line[0]][0]
    }

    fn add_side_nodes(&mut self, line: &[usize]) {
        self.sides[0].push(line[0]);
        self.sides[1].push(*line.last().expect("a line has nodes"));
    }

    fn add_node(&mut self, x: [f64; 2]) -> usize {
        self.nodes.push(x);
        self.nodes.len() - 1
    }

    /// A row of quads from the nodes `line` up to a line of nodes at the same `X` at height
    /// `y1`; returns that line.
    fn plain_row(&mut self, line: &[usize], y1: f64) -> Vec<usize> {
        let upper: Vec<usize> = line
            .iter()
            .map(|&n| self.add_node([self.nodes[n][0], y1]))
            .collect();
        for i in 0..line.len() - 1 {
            self.quads
                .push([line[i], line[i + 1], upper[i + 1], upper[i]]);
        }
        upper
    }

    /// A row that joins every [`TRANSITION_COLUMNS`] columns of `line` into one: per group, the
    /// conforming template of four quads (two nodes at mid-height above the group's inner
    /// nodes; below, two quads beside one between them; above, one across the group). The
    /// columns left over at `X = ½` (fewer than a group) continue as plain quads. Returns the
    /// upper line of nodes at height `y1`.
    fn transition_row(&mut self, line: &[usize], y0: f64, y1: f64) -> Vec<usize> {
        let xs: Vec<f64> = line.iter().map(|&n| self.nodes[n][0]).collect();
        let columns = line.len() - 1;
        let groups = columns / TRANSITION_COLUMNS;
        let mut upper: Vec<usize> = (0..=groups)
            .map(|g| self.add_node([xs[TRANSITION_COLUMNS * g], y1]))
            .collect();
        let y_mid = 0.5 * (y0 + y1);
        for g in 0..groups {
            let first = TRANSITION_COLUMNS * g;
            let t = &line[first..=first + TRANSITION_COLUMNS];
            let m1 = self.add_node([xs[first + 1], y_mid]);
            let m2 = self.add_node([xs[first + 2], y_mid]);
            let (b0, b3) = (upper[g], upper[g + 1]);
            self.quads.push([t[0], t[1], m1, b0]);
            self.quads.push([t[1], t[2], m2, m1]);
            self.quads.push([t[2], t[3], b3, m2]);
            self.quads.push([m1, m2, b3, b0]);
        }
        for i in TRANSITION_COLUMNS * groups..columns {
            let right = self.add_node([xs[i + 1], y1]);
            let left = *upper.last().expect("the group's last node");
            self.quads.push([line[i], line[i + 1], right, left]);
            upper.push(right);
        }
        upper
    }
}

/// Columns a transition row joins into one.
const TRANSITION_COLUMNS: usize = 3;

/// Layer interfaces `0 = y₀ < … < y_n = h` with geometric growth and first layer `t0`
/// (uniform if `n t0 ≥ h`).
fn geometric_layers(n: usize, h: f64, t0: f64) -> Vec<f64> {
    if t0 * n as f64 >= h {
        return (0..=n).map(|j| h * j as f64 / n as f64).collect();
    }
    // solve t0 (rⁿ − 1)/(r − 1) = h for r > 1 by bisection
    let total = |r: f64| t0 * (r.powi(n as i32) - 1.0) / (r - 1.0);
    let (mut lo, mut hi) = (1.0 + 1e-12, 2.0);
    while total(hi) < h {
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if total(mid) < h {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let r = 0.5 * (lo + hi);
    let mut ys = Vec::with_capacity(n + 1);
    let mut y = 0.0;
    let mut t = t0;
    ys.push(0.0);
    for _ in 0..n {
        y += t;
        t *= r;
        ys.push(y);
    }
    let scale = h / y;
    for v in &mut ys {
        *v *= scale;
    }
    ys
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    fn shoelace(m: &Mesh, q: &[usize; 4]) -> f64 {
        (0..4)
            .map(|k| {
                let (a, b) = (m.nodes[q[k]], m.nodes[q[(k + 1) % 4]]);
                0.5 * (a[0] * b[1] - b[0] * a[1])
            })
            .sum()
    }

    /// Every edge of the mesh and how many quads hold it.
    fn edge_counts(m: &Mesh) -> HashMap<(usize, usize), usize> {
        let mut edges = HashMap::new();
        for q in &m.quads {
            for k in 0..4 {
                let (a, b) = (q[k], q[(k + 1) % 4]);
                *edges.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            }
        }
        edges
    }

    /// A coarsened mesh tiles the layer conformingly: positive quads whose areas sum to the
    /// layer's, every edge inside the layer shared by two quads and every edge held by one
    /// quad on the layer's boundary, the columns fewer at the bonded face.
    #[test]
    fn coarsened_mesh_is_conforming() {
        for (nx, coarsen) in [(48, 3.0), (64, 2.0), (50, 1.5)] {
            let grading = Grading {
                peak_ratio: 4.0,
                first_layer_over_dx: 1.0,
                coarsen_at_aspect: coarsen,
            };
            let m = Mesh::graded(nx, nx / 2, 1.0, grading);
            let areas: Vec<f64> = m.quads.iter().map(|q| shoelace(&m, q)).collect();
            assert!(
                areas.iter().all(|&a| a > 0.0),
                "nx {nx}: a quad is not positive"
            );
            let total: f64 = areas.iter().sum();
            assert!((total - 0.5).abs() < 1e-12, "nx {nx}: area {total}");
            let on_boundary = |n: usize| {
                let [x, y] = m.nodes[n];
                x == 0.0 || x == 0.5 || y == 0.0 || (y - 1.0).abs() < 1e-12
            };
            for ((a, b), count) in edge_counts(&m) {
                match count {
                    1 => assert!(on_boundary(a) && on_boundary(b), "hanging edge {a}–{b}"),
                    2 => {}
                    _ => panic!("edge {a}–{b} in {count} quads"),
                }
            }
            assert!(m.top.len() < m.bottom.len() / 2, "nx {nx}: not coarsened");
            assert_eq!(m.above_bottom.len(), m.bottom.len());
            assert_eq!(m.sides[0].len(), m.ny + 1);
            assert!(m.sides[1].iter().all(|&n| m.nodes[n][0] == 0.5));
        }
    }

    /// The two-scale scenes' meshes (uniform face, a quarter as many rows as face elements,
    /// coarsened where the rows reach 4× their width) keep three fifths of their nodes, a
    /// single sinusoid's 192 × 96 and 512 × 256 three quarters: the counts docs/replication.md
    /// (R13) and docs/performance.md quote.
    #[test]
    fn coarsened_mesh_node_counts() {
        let counts = [
            (320, 80, 15_093),
            (192, 48, 5_539),
            (192, 96, 13_857),
            (512, 256, 96_821),
        ];
        for (nx, ny, coarsened) in counts {
            let grading = Grading {
                coarsen_at_aspect: 4.0,
                ..Grading::uniform_face()
            };
            let m = Mesh::graded(nx, ny, 1.0, grading);
            assert_eq!(m.nodes.len(), coarsened, "{nx} × {ny}");
            let full = Mesh::graded(nx, ny, 1.0, Grading::uniform_face());
            assert_eq!(full.nodes.len(), (nx + 1) * (ny + 1));
        }
    }

    /// Up to AR 0.3 a sinusoid keeps the grading it is given; beyond, `1 + peak_ratio` grows
    /// as the square of the peak's stretch, for the default and for a uniform face alike.
    #[test]
    fn a_steep_sinusoid_grades_its_peak_finer() {
        for ar in [0.05, 0.2, 0.3] {
            assert_eq!(Grading::default().for_sinusoid(ar), Grading::default());
        }
        let at = |g: Grading, ar: f64| g.for_sinusoid(ar).peak_ratio;
        assert!((at(Grading::default(), 0.35) - 7.98).abs() < 0.01);
        assert!((at(Grading::default(), 0.4) - 15.14).abs() < 0.01);
        let squared = (5.12_f64 / 2.85).powi(2);
        assert!(((1.0 + at(Grading::default(), 0.4)) / 5.0 / squared - 1.0).abs() < 1e-3);
        assert!(((1.0 + at(Grading::uniform_face(), 0.4)) / 2.0 / squared - 1.0).abs() < 1e-3);
        let steep = Grading::default().for_sinusoid(0.4);
        assert_eq!(
            steep.first_layer_over_dx,
            Grading::default().first_layer_over_dx
        );
    }

    /// Without coarsening the mesh is the structured grid: node `(i, j)` has id `j (nx+1) + i`.
    #[test]
    fn uncoarsened_mesh_is_the_structured_grid() {
        let m = Mesh::graded(6, 3, 1.0, Grading::default());
        assert_eq!(m.nodes.len(), 7 * 4);
        assert_eq!(m.quads[7], [8, 9, 16, 15]);
        assert_eq!(m.above_bottom, (7..14).collect::<Vec<_>>());
        assert_eq!(m.top, (21..28).collect::<Vec<_>>());
        assert_eq!(m.sides[1], vec![6, 13, 20, 27]);
    }
}
