//! Contact patches and the contact fraction, with each patch edge placed between grid points.
//!
//! Near an edge of a frictionless elastic contact the gap grows like the 3/2 power of the
//! distance out of the contact, so `g^{2/3}` is locally linear and extrapolates to zero at the
//! edge; across a short opening between two contacts it is close to a parabola vanishing at both
//! edges (`g ∝ ((x − e₁)(e₂ − x))^{3/2}`, the near-full-contact form of Westergaard's solution).
//! The grid values right beside an edge carry the discretisation's local oscillation (the
//! pressure in the last contact points swings by some 10 % about the √distance law, the first open
//! gap is off by a factor of several), so the fits read the gap a little further out:
//!
//! - an opening of at least 10 points: the parabola through the 3rd, 4th and 5th open points;
//! - 5 to 9 points: the least-squares parabola through all but the first and last open points,
//!   whose roots are the opening's two edges;
//! - 3 or 4 points: the same through all of them;
//! - shorter, or when a fit has no root between one grid step inside and two outside the last
//!   contact point: halfway between the last contact point and the first open one.
//!
//! Measured against Westergaard (`src/bem/solver_tests.rs`), the edge is then within a few hundredths of
//! a grid step of the exact one at every grid (halfway: up to 0.5): still first order in `1/N`,
//! as the discrete solution itself is, with a constant more than ten times smaller.

/// The contact intervals `[start, end]` in `x ∈ [0, ½]` of an even grid solution (`N` points on
/// one wavelength, `N` even; contact where the pressure is positive). A patch through `x = 0`
/// starts at 0, one through `x = ½` ends at ½.
pub(super) fn patches(pressure: &[f64], gap: &[f64]) -> Vec<[f64; 2]> {
    let n = pressure.len();
    let half = n / 2;
    let h = 1.0 / n as f64;
    let contact = |i: usize| pressure[i] > 0.0;
    let mut out = vec![];
    let mut i = 0;
    while i <= half {
        if !contact(i) {
            i += 1;
            continue;
        }
        let first = i;
        while i < half && contact(i + 1) {
            i += 1;
        }
        let last = i;
        let start = if first == 0 {
            0.0
        } else {
            edge(pressure, gap, first, -1) * h
        };
        let end = if last == half {
            0.5
        } else {
            edge(pressure, gap, last, 1) * h
        };
        out.push([start, end]);
        i += 1;
    }
    out
}

/// The edge beyond the contact point `c` in the direction `d` (±1), in grid units: `c + d t`,
/// `t` the offset where `g^{2/3}` reaches zero (module doc).
fn edge(pressure: &[f64], gap: &[f64], c: usize, d: isize) -> f64 {
    let n = pressure.len() as isize;
    let at = |k: usize| (c as isize + k as isize * d).rem_euclid(n) as usize;
    // open points beyond c (the solution is periodic and even, so this may run through x = ½)
    let opening = (1..pressure.len())
        .take_while(|&k| pressure[at(k)] == 0.0)
        .count();
    let v = |k: usize| gap[at(k)].max(0.0).powf(2.0 / 3.0);
    let fitted = match opening {
        0..=2 => None,
        3..=4 => lower_root(&(1..=opening).map(|k| (k as f64, v(k))).collect::<Vec<_>>()),
        5..=9 => lower_root(&(2..opening).map(|k| (k as f64, v(k))).collect::<Vec<_>>()),
        _ => lower_root(&[(3.0, v(3)), (4.0, v(4)), (5.0, v(5))]),
    };
    let t = fitted.filter(|t| (-1.0..=2.0).contains(t)).unwrap_or(0.5);
    c as f64 + d as f64 * t
}

/// The smaller root of the least-squares parabola through `points` (at least 3, distinct `t`),
/// if it has real roots and rises through the smaller one.
fn lower_root(points: &[(f64, f64)]) -> Option<f64> {
    let m = points.len() as f64;
    let centre = points.iter().map(|p| p.0).sum::<f64>() / m;
    // normal equations of v ≈ a + b s + c s², s = t − centre
    let mut sums = [0.0; 5];
    let mut rhs = [0.0; 3];
    for &(t, v) in points {
        let s = t - centre;
        let mut power = 1.0;
        for (j, sum) in sums.iter_mut().enumerate() {
            *sum += power;
            if j < 3 {
                rhs[j] += power * v;
            }
            power *= s;
        }
    }
    let matrix = [
        [sums[0], sums[1], sums[2]],
        [sums[1], sums[2], sums[3]],
        [sums[2], sums[3], sums[4]],
    ];
    let det = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let full = det(matrix);
    let column = |j: usize| {
        let mut m = matrix;
        for (row, r) in m.iter_mut().zip(rhs) {
            row[j] = r;
        }
        det(m) / full
    };
    let (a, b, c) = (column(0), column(1), column(2));
    // a + b s + c s² = 0; the root where the parabola rises (slope b + 2cs > 0) is the lower
    // edge of the opening
    let disc = b * b - 4.0 * a * c;
    if !(full.is_normal() && disc >= 0.0) {
        return None;
    }
    let root = if c.abs() < 1e-12 * b.abs() {
        -a / b
    } else {
        let q = -0.5 * (b + b.signum() * disc.sqrt());
        let (r1, r2) = (q / c, a / q);
        if b + 2.0 * c * r1 > 0.0 {
            r1
        } else {
            r2
        }
    };
    (b + 2.0 * c * root > 0.0 && root.is_finite()).then_some(centre + root)
}
