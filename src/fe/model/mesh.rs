//! Structured quad mesh of the half-wavelength layer, graded toward the contact face
//! and toward the indenter's peak.
//!
//! Domain (units of λ): `X ∈ [0, ½]`, `Y ∈ [0, h]`; the contact face is `Y = 0`, the
//! bonded face `Y = h`. Node `(i, j)` (column `i ∈ 0..=nx`, row `j ∈ 0..=ny`) has id
//! `j (nx+1) + i`. Quads are counter-clockwise.
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
    /// Spacing ratio along the contact face: `ΔX(½) / ΔX(0)` (≥ 1).
    pub peak_ratio: f64,
    /// Bottom layer thickness in units of the mean face spacing `½/nx`.
    pub first_layer_over_dx: f64,
}

impl Grading {
    /// Uniform spacing along the contact face (`peak_ratio` 1), the default layers: the mesh of
    /// a profile whose small waves touch anywhere on the face.
    pub fn uniform_face() -> Self {
        Self {
            peak_ratio: 1.0,
            ..Self::default()
        }
    }
}

impl Default for Grading {
    fn default() -> Self {
        Self {
            peak_ratio: 4.0,
            first_layer_over_dx: 1.0,
        }
    }
}

/// Structured mesh.
#[derive(Clone, Debug)]
pub struct Mesh {
    /// Elements along `X`.
    pub nx: usize,
    /// Elements along `Y`.
    pub ny: usize,
    /// Layer thickness `h/λ`.
    pub thickness: f64,
    /// Reference node coordinates.
    pub nodes: Vec<[f64; 2]>,
    /// Quads (node ids, counter-clockwise).
    pub quads: Vec<[usize; 4]>,
    /// Contact-face nodes in order of increasing `X`.
    pub bottom: Vec<usize>,
    /// Bonded-face nodes in order of increasing `X`.
    pub top: Vec<usize>,
}

impl Mesh {
    /// Build the graded mesh.
    pub fn graded(nx: usize, ny: usize, thickness: f64, grading: Grading) -> Self {
        let beta = ((grading.peak_ratio - 1.0) / 2.0).max(0.0);
        let xs: Vec<f64> = (0..=nx)
            .map(|i| {
                let xi = i as f64 / nx as f64;
                0.5 * (xi + beta * xi * xi) / (1.0 + beta)
            })
            .collect();
        let ys = geometric_layers(ny, thickness, grading.first_layer_over_dx * 0.5 / nx as f64);
        let mut nodes = Vec::with_capacity((nx + 1) * (ny + 1));
        for &y in &ys {
            for &x in &xs {
                nodes.push([x, y]);
            }
        }
        let id = |i: usize, j: usize| j * (nx + 1) + i;
        let mut quads = Vec::with_capacity(nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                quads.push([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        Self {
            nx,
            ny,
            thickness,
            nodes,
            quads,
            bottom: (0..=nx).map(|i| id(i, 0)).collect(),
            top: (0..=nx).map(|i| id(i, ny)).collect(),
        }
    }

    /// Node id of column `i`, row `j`.
    pub fn id(&self, i: usize, j: usize) -> usize {
        j * (self.nx + 1) + i
    }
}

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
