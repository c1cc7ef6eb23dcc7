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
        let mut planner = FftPlanner::new();
        let forward = planner.plan_fft_forward(n);
        let inverse = planner.plan_fft_inverse(n);
        let weights = (0..n)
            .map(|k| match k.min(n - k) {
                0 => Ok(0.0),
                m => {
                    let q = std::f64::consts::TAU * m as f64;
                    Ok(body.over_half_plane(q)? * half_plane(q) / n as f64)
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

    /// `out = K p`.
    pub(super) fn apply(&mut self, p: &[f64], out: &mut [f64]) {
        for (b, &v) in self.buffer.iter_mut().zip(p) {
            *b = Complex::new(v, 0.0);
        }
        self.forward
            .process_with_scratch(&mut self.buffer, &mut self.scratch);
        for (b, &w) in self.buffer.iter_mut().zip(&self.weights) {
            *b *= w;
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
}
