//! The elastic body's compliance on the periodic grid: displacement from pressure by FFT.

use std::sync::Arc;

use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

use super::compliance::{half_plane, ElasticBody};
use super::BemError;

/// `u = K p` on `N` equally spaced points of one wavelength: each discrete Fourier harmonic of
/// index `k` (wavenumber `q = 2π min(k, N − k)`, λ = 1) of the pressure is scaled by the body's
/// compliance (the half-plane's `2/(E* q)`, a layer's `S(qh, ν)` times that); the mean (`k = 0`)
/// is dropped, so `u` has zero mean and the rigid approach stays a separate unknown. Units: `p`
/// over E*, `u` over λ.
pub(super) struct GridCompliance {
    forward: Arc<dyn Fft<f64>>,
    inverse: Arc<dyn Fft<f64>>,
    /// `C(q_k)/N` (the inverse FFT's normalisation folded in); 0 at `k = 0`.
    weights: Vec<f64>,
    buffer: Vec<Complex<f64>>,
    scratch: Vec<Complex<f64>>,
}

impl GridCompliance {
    /// The half-plane's operator for `n` points (`n ≥ 2`).
    #[cfg(test)]
    pub(super) fn new(n: usize) -> Self {
        Self::on(n, ElasticBody::HalfPlane).expect("the half-plane's compliance")
    }

    /// The operator of `body` for `n` points (`n ≥ 2`).
    pub(super) fn on(n: usize, body: ElasticBody) -> Result<Self, BemError> {
        Self::scaled(n, |q| body.over_half_plane(q))
    }

    /// The half-plane's operator with each harmonic scaled by `ratio(q)` (`q` in 1/λ): a body's
    /// compliance over the half-plane's, or one entry of its [`super::HarmonicCompliance`].
    pub(super) fn scaled(
        n: usize,
        ratio: impl Fn(f64) -> Result<f64, BemError>,
    ) -> Result<Self, BemError> {
        let mut planner = FftPlanner::new();
        let forward = planner.plan_fft_forward(n);
        let inverse = planner.plan_fft_inverse(n);
        let weights = (0..n)
            .map(|k| match k.min(n - k) {
                0 => Ok(0.0),
                m => {
                    let q = std::f64::consts::TAU * m as f64;
                    Ok(ratio(q)? * half_plane(q) / n as f64)
                }
            })
            .collect::<Result<Vec<f64>, BemError>>()?;
        let scratch_len = forward
            .get_inplace_scratch_len()
            .max(inverse.get_inplace_scratch_len());
        Ok(Self {
            forward,
            inverse,
            weights,
            buffer: vec![Complex::default(); n],
            scratch: vec![Complex::default(); scratch_len],
        })
    }

    /// `K`'s diagonal: the displacement at a point per unit pressure there (all weights summed).
    pub(super) fn diagonal(&self) -> f64 {
        self.weights.iter().sum()
    }

    /// Whether the operator is zero (every harmonic's weight 0).
    pub(super) fn is_zero(&self) -> bool {
        self.weights.iter().all(|&w| w == 0.0)
    }

    /// `out = K p`.
    pub(super) fn apply(&mut self, p: &[f64], out: &mut [f64]) {
        self.transform(p, out, |b, _, w| *b *= w);
    }

    /// `out = K H v`: each harmonic of `v` scaled by the compliance and by the Hilbert
    /// transform's symbol `−i sign(k)` (`H cos = sin`, `H sin = −cos`; `(H v)(x) = (1/π) PV∫
    /// v(s)/(x − s) ds` on the period), the Nyquist harmonic dropped (its sine vanishes on the
    /// grid). Built with a body's coupling ratio, this is its normal–tangential coupling
    /// ([`super::frictional_contact`]).
    pub(super) fn apply_hilbert(&mut self, v: &[f64], out: &mut [f64]) {
        let n = self.weights.len();
        self.transform(v, out, |b, k, w| {
            *b *= match (2 * k).cmp(&n) {
                std::cmp::Ordering::Less => Complex::new(0.0, -w),
                std::cmp::Ordering::Greater => Complex::new(0.0, w),
                std::cmp::Ordering::Equal => Complex::new(0.0, 0.0),
            }
        });
    }

    /// `out = F⁻¹ diag F v`, each harmonic `b_k` of `F v` scaled in place by `scale(b_k, k, w_k)`.
    fn transform(
        &mut self,
        v: &[f64],
        out: &mut [f64],
        scale: impl Fn(&mut Complex<f64>, usize, f64),
    ) {
        for (b, &x) in self.buffer.iter_mut().zip(v) {
            *b = Complex::new(x, 0.0);
        }
        self.forward
            .process_with_scratch(&mut self.buffer, &mut self.scratch);
        for (k, (b, &w)) in self.buffer.iter_mut().zip(&self.weights).enumerate() {
            scale(b, k, w);
        }
        self.inverse
            .process_with_scratch(&mut self.buffer, &mut self.scratch);
        for (o, b) in out.iter_mut().zip(&self.buffer) {
            *o = b.re;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A pressure harmonic `cos 2πkx` gives the displacement `(2/(2πk)) cos 2πkx`, to rounding.
    #[test]
    fn a_harmonic_is_scaled_by_the_half_plane_compliance() {
        let n = 64;
        let mut k_op = GridCompliance::new(n);
        let x = |i: usize| i as f64 / n as f64;
        for k in [1usize, 5, 31, 32] {
            let p: Vec<f64> = (0..n)
                .map(|i| 0.7 + (std::f64::consts::TAU * k as f64 * x(i)).cos())
                .collect();
            let mut u = vec![0.0; n];
            k_op.apply(&p, &mut u);
            for (i, &ui) in u.iter().enumerate() {
                let want = 2.0 / (std::f64::consts::TAU * k as f64)
                    * (std::f64::consts::TAU * k as f64 * x(i)).cos();
                assert!(
                    (ui - want).abs() < 1e-15,
                    "k = {k}, i = {i}: {ui} vs {want}"
                );
            }
        }
    }

    /// `K H cos 2πkx = (2/(2πk)) sin 2πkx` and `K H sin 2πkx = −(2/(2πk)) cos 2πkx`: the
    /// Hilbert transform's pairs (Johnson, *Contact Mechanics*, eqs. 2.25) through the
    /// compliance.
    #[test]
    fn the_hilbert_operator_turns_cosines_into_sines() {
        let n = 64;
        let mut k_op = GridCompliance::new(n);
        let x = |i: usize| i as f64 / n as f64;
        for k in [1usize, 3, 31] {
            let w = 2.0 / (std::f64::consts::TAU * k as f64);
            let arg = |i: usize| std::f64::consts::TAU * k as f64 * x(i);
            let cos: Vec<f64> = (0..n).map(|i| arg(i).cos()).collect();
            let sin: Vec<f64> = (0..n).map(|i| arg(i).sin()).collect();
            let mut out = vec![0.0; n];
            k_op.apply_hilbert(&cos, &mut out);
            for i in 0..n {
                assert!((out[i] - w * sin[i]).abs() < 1e-15, "cos, k = {k}, i = {i}");
            }
            k_op.apply_hilbert(&sin, &mut out);
            for i in 0..n {
                assert!((out[i] + w * cos[i]).abs() < 1e-15, "sin, k = {k}, i = {i}");
            }
        }
    }
}
