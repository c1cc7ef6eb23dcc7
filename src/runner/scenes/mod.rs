//! The one list of scenes, and what a scene is.
//!
//! A scene is a section type (`[fe_vs_model]`, …) that validates itself and turns into tables
//! and a figure. Adding one takes a TOML file in `experiments/`, one file
//! `src/runner/scenes/<table>.rs` (or a folder `<table>/`) that defines its section type and
//! implements [`Scene`], its `pub mod` line below, and one line in the `scene_registry!`
//! invocation below: the registry generates the whole-file type [`Spec`] (one optional table per
//! scene, named like its module), the "exactly one scene table" rule and its message. The
//! modules are declared outside the macro so that rustfmt formats them.

pub mod correction_surfaces;
pub mod deformed_mesh;
pub(crate) mod fe_inverse;
pub mod fe_vs_model;
pub mod fingertip_area;
pub mod fingertip_fe;
pub mod fingertip_ridges;
pub mod hysteresis;
pub mod many_scale;
pub(crate) mod profile_comparison;
pub(crate) mod scene_output;
pub mod speed_accuracy;
pub mod table1_refit;
pub mod two_scale;
pub(crate) mod wnl_beyond_fit;

use crate::plot::Figure;
use crate::runner::sweep::fe_cases::FeCase;
use crate::runner::RunOptions;
use crate::spec::{parse_document, Location, SpecError, Validator};
use crate::table::Table;
use std::path::Path;

/// What a scene needs besides its section.
pub struct SceneContext<'a> {
    /// The spec's title (the figure caption).
    pub title: &'a str,
    /// The spec's folder: relative data paths are resolved against it.
    pub spec_dir: &'a Path,
    pub opts: &'a RunOptions,
}

/// What a scene computes, before anything is written.
#[derive(Debug, Clone)]
pub struct SceneResult {
    /// Its tables: the first is `<stem>.csv`, the others `<stem>_<name>.csv`.
    pub tables: Vec<Table>,
    /// Its figure (caption, panels and footer).
    pub figure: Figure,
    /// What the reader must know (missing data, extrapolation), printed with the run's output.
    pub notes: Vec<String>,
    /// Finite-element curves that stopped short of their target, each with the reason. The
    /// figure and tables say so; `wavy check` and the snapshot test fail on any.
    pub incomplete: Vec<String>,
}

/// One kind of experiment: a spec section that validates itself and runs.
pub trait Scene: std::fmt::Debug + Sync {
    /// Checks what deserialising could not (grid ranges, non-empty lists, cross-field rules).
    fn validate(&self, v: &Validator) -> Result<(), SpecError>;

    /// The finite-element curves the scene needs, so that a sharded run can compute its share
    /// into the cache (none by default).
    fn fe_cases(&self, _opts: &RunOptions) -> Vec<FeCase> {
        Vec::new()
    }

    /// Computes the scene's tables and figure.
    fn run(&self, ctx: &SceneContext) -> anyhow::Result<SceneResult>;
}

/// Generates [`Spec`] from the list `module::SectionType`: the scene's table in a spec is named
/// like its module.
macro_rules! scene_registry {
    ($($table:ident :: $section:ident),+ $(,)?) => {
        /// A whole spec file: a title, the `[check]` tolerances, and exactly one scene table.
        #[derive(Debug, Clone, serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        pub struct Spec {
            /// Figure title.
            pub title: String,
            /// How `wavy check` compares a recomputation with `expected/`.
            pub check: $crate::spec::CheckTolerance,
            $(
                #[doc = concat!("The `[", stringify!($table), "]` scene.")]
                pub $table: Option<$table::$section>,
            )+
        }

        impl Spec {
            /// The scene tables a spec may hold, in registry order.
            pub const SCENE_TABLES: &'static [&'static str] = &[$(stringify!($table)),+];

            /// The scene tables present in this file.
            fn present(&self) -> Vec<&dyn Scene> {
                let mut present: Vec<&dyn Scene> = Vec::new();
                $(
                    if let Some(s) = &self.$table {
                        present.push(s);
                    }
                )+
                present
            }
        }
    };
}

// The one list of scenes: `module::SectionType`, one line each.
scene_registry! {
    correction_surfaces::CorrectionSurfacesScene,
    fe_vs_model::FeVsModelScene,
    fingertip_area::FingertipAreaScene,
    fingertip_fe::FingertipFeScene,
    deformed_mesh::DeformedMeshScene,
    table1_refit::Table1RefitScene,
    speed_accuracy::SpeedAccuracyScene,
    hysteresis::HysteresisScene,
    two_scale::TwoScaleScene,
    many_scale::ManyScaleScene,
}

impl Spec {
    /// Parses and validates a spec. `origin` names the file in error messages.
    pub fn parse(text: &str, origin: &str) -> Result<Spec, SpecError> {
        let spec: Spec = parse_document(text, origin)?;
        let n = spec.present().len();
        if n != 1 {
            let tables: Vec<String> = Self::SCENE_TABLES
                .iter()
                .map(|t| format!("[{t}]"))
                .collect();
            return Err(SpecError::Invalid {
                origin: origin.into(),
                field: "(scene table)".into(),
                location: Location(None),
                value: format!("{n} scene tables"),
                allowed: format!("exactly one of {}", tables.join(", ")),
            });
        }
        spec.scene().validate(&Validator { text, origin })?;
        Ok(spec)
    }

    /// The one scene of this spec.
    pub fn scene(&self) -> &dyn Scene {
        self.present()
            .into_iter()
            .next()
            .expect("Spec::parse admits exactly one scene table")
    }
}
