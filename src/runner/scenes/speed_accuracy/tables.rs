//! The tables of the speed–accuracy scene: each tier's measurement, the reference of each case,
//! each tier's largest error per a/λ band, and what halving the FE error costs at each case.

use crate::accuracy::measured::PHYSICS_COLUMNS;
use crate::accuracy::{relative_errors, Tier};
use crate::runner::scenes::speed_accuracy::case_reference::Reference;
use crate::runner::scenes::speed_accuracy::tier_measurement::{ErrorTimeTrade, Measurement};
use crate::table::{Cell, Table};

/// The scene's four tables: each tier's measurement, the reference of each case, each tier's
/// largest error per a/λ band, and what halving the FE error costs at each case.
pub(in crate::runner) struct Tables {
    scene: SceneColumns,
    main: Table,
    reference: Table,
    bands: Table,
    trade: Table,
}

/// What the tables repeat of the scene's spec.
pub(in crate::runner) struct SceneColumns {
    /// The a/λ grid of the errors.
    pub a_over_lambda: Vec<f64>,
    /// The a/λ band edges.
    pub error_bands: Vec<f64>,
    pub order_meshes: [usize; 3],
    pub reference_meshes: Vec<usize>,
    /// The physics, in the order of `PHYSICS_COLUMNS`.
    pub physics: [f64; 5],
}

impl Tables {
    pub fn new(scene: SceneColumns) -> Self {
        let mut reference_header = vec!["aspect_ratio", "tau_max_mpa"];
        reference_header.extend(PHYSICS_COLUMNS);
        reference_header.extend([
            "a_over_lambda_min",
            "a_over_lambda_max",
            "order_meshes",
            "observed_order",
            "order_used",
            "reference_meshes",
            "reference_uncertainty",
        ]);
        Tables {
            scene,
            main: Table::new("", &MAIN_HEADER),
            reference: Table::new("reference", &reference_header),
            bands: Table::new("bands", &BANDS_HEADER),
            trade: Table::new("trade", &TRADE_HEADER),
        }
    }

    pub fn push_trade(&mut self, trade: Option<&ErrorTimeTrade>, ar: f64, tau: f64) {
        let tiers = trade.map(|t| {
            t.tiers
                .iter()
                .map(|t| t.name())
                .collect::<Vec<_>>()
                .join(" ")
        });
        self.trade.push(vec![
            ar.into(),
            tau.into(),
            tiers.unwrap_or_default().into(),
            trade.map(|t| t.exponent).into(),
            trade.map(|t| t.time_factor_per_halving).into(),
        ]);
    }

    pub fn push_reference(&mut self, r: &Reference, ar: f64, tau: f64) {
        let s = &self.scene;
        let xs = &s.a_over_lambda;
        let [order_mesh, coarse, fine] = s.order_meshes;
        let meshes: Vec<String> = s.reference_meshes.iter().map(|n| n.to_string()).collect();
        let mut row: Vec<Cell> = vec![ar.into(), tau.into()];
        row.extend(s.physics.map(Cell::from));
        row.extend([
            xs[0].into(),
            xs[xs.len() - 1].into(),
            format!("{order_mesh} {coarse} {fine}").into(),
            r.observed_order.into(),
            r.order_used.into(),
            meshes.join(" ").into(),
            r.uncertainty.into(),
        ]);
        self.reference.push(row);
    }

    /// The largest error of `tier`'s `values` against `reference` in each a/λ band.
    pub fn push_bands(
        &mut self,
        tier: &Tier,
        values: Option<&[f64]>,
        reference: &[f64],
        ar: f64,
        tau: f64,
    ) {
        let xs = &self.scene.a_over_lambda;
        for band in self.scene.error_bands.windows(2) {
            let in_band: Vec<usize> = (0..xs.len())
                .filter(|&i| band[0] <= xs[i] && xs[i] <= band[1])
                .collect();
            let error = values.map(|v| {
                let pick = |w: &[f64]| in_band.iter().map(|&i| w[i]).collect::<Vec<_>>();
                relative_errors(&pick(v), &pick(reference)).max
            });
            self.bands.push(vec![
                tier.name().into(),
                ar.into(),
                tau.into(),
                band[0].into(),
                band[1].into(),
                error.into(),
            ]);
        }
    }

    pub fn push_measurements(&mut self, ms: &[Measurement], front: &[usize], ar: f64, tau: f64) {
        for (i, m) in ms.iter().enumerate() {
            self.main.push(vec![
                m.tier.name().into(),
                ar.into(),
                tau.into(),
                m.status.clone().into(),
                m.errors.map(|e| e.max).into(),
                m.errors.map(|e| e.rms).into(),
                m.seconds_per_curve.into(),
                m.seconds_per_point.into(),
                m.fe.as_ref().map(|f| f.dofs as f64).into(),
                m.fe.as_ref().map(|f| f.load_steps as f64).into(),
                m.fe.as_ref().map(|f| f.newton_iterations as f64).into(),
                front.contains(&i).into(),
            ]);
        }
    }

    pub fn into_vec(self) -> Vec<Table> {
        vec![self.main, self.reference, self.bands, self.trade]
    }
}

const MAIN_HEADER: [&str; 12] = [
    "tier",
    "aspect_ratio",
    "tau_max_mpa",
    "status",
    "max_rel_error",
    "rms_rel_error",
    "seconds_per_curve",
    "seconds_per_point",
    "dofs",
    "load_steps",
    "newton_iterations",
    "pareto",
];

const BANDS_HEADER: [&str; 6] = [
    "tier",
    "aspect_ratio",
    "tau_max_mpa",
    "a_over_lambda_from",
    "a_over_lambda_to",
    "max_rel_error",
];

const TRADE_HEADER: [&str; 5] = [
    "aspect_ratio",
    "tau_max_mpa",
    "fe_tiers",
    "error_time_exponent",
    "time_factor_per_halving",
];
