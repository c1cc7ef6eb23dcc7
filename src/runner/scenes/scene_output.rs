//! The tail every scene's `run` shares, written once: the figure's footer and the run's notes as
//! they accumulate, the finite-element curves that stopped short of their target, and the
//! assembly of the figure and the [`SceneResult`].

use crate::numfmt::sig_digits;
use crate::plot::{Figure, Panel};
use crate::runner::scenes::SceneResult;
use crate::runner::sweep::fe_cases::FeOutcome;
use crate::table::Table;

/// How a scene's panels are laid out.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Layout {
    /// Panel rows and columns.
    pub grid: (usize, usize),
    /// Width and height of one panel, px.
    pub panel_px: (u32, u32),
    /// Height added under the panels for the caption and the footer, px.
    pub margin_px: u32,
    pub font_px: u32,
}

/// What a run says besides its tables and panels.
#[derive(Debug, Clone, Default)]
pub(crate) struct Remarks {
    /// Lines under the panels.
    pub footer: Vec<String>,
    /// Printed with the run's output ([`SceneResult::notes`]).
    pub notes: Vec<String>,
    /// FE curves that stopped short of their target ([`SceneResult::incomplete`]).
    pub incomplete: Vec<String>,
}

impl Remarks {
    /// Remarks that start with these footer lines.
    pub fn with_footer(footer: Vec<String>) -> Self {
        Remarks {
            footer,
            ..Remarks::default()
        }
    }

    /// A remark the figure's footer and the run's output both carry.
    pub fn footer_and_note(&mut self, note: String) {
        self.footer.push(note.clone());
        self.notes.push(note);
    }

    /// Records the FE curve named `label` when it stopped short of its target.
    pub fn stopped_curve(&mut self, label: &str, fe: &FeOutcome) {
        if let Some(f) = &fe.failure {
            self.incomplete.push(format!(
                "FE curve {label} stopped at a/λ = {}: {f}",
                sig_digits(fe.last_a_over_lambda(), 4)
            ));
        }
    }

    /// The footer line that counts the incomplete FE curves, followed by `where_told` (where
    /// the figure and tables mark them); none when every curve is complete.
    pub fn count_incomplete(&mut self, where_told: &str) {
        if !self.incomplete.is_empty() {
            self.footer.push(format!(
                "INCOMPLETE FE curves ({}): {where_told}.",
                self.incomplete.len()
            ));
        }
    }

    /// The scene's result: `panels` laid out under `title` with the footer, and `tables`.
    pub fn finish(
        self,
        title: &str,
        layout: Layout,
        panels: Vec<Panel>,
        tables: Vec<Table>,
    ) -> SceneResult {
        let (rows, cols) = layout.grid;
        let figure = Figure {
            width: layout.panel_px.0 * cols as u32,
            height: layout.panel_px.1 * rows as u32 + layout.margin_px,
            caption: title.into(),
            grid: layout.grid,
            panels,
            footer: self.footer,
            font_px: layout.font_px,
        };
        SceneResult {
            tables,
            figure,
            notes: self.notes,
            incomplete: self.incomplete,
        }
    }
}

/// The panel note of an FE curve that stopped short of its target; none for a complete one.
pub(crate) fn incomplete_panel_note(fe: &FeOutcome) -> Option<String> {
    fe.failure.as_ref().map(|_| {
        format!(
            "FE INCOMPLETE: stopped at a/λ = {}",
            sig_digits(fe.last_a_over_lambda(), 3)
        )
    })
}
