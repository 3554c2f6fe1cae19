//! Why the live models refuse a setting, in one line for the user.

use spintop::math::Real;

/// Why the live models refused a setting (a key, an edit, an experiment of
/// the book, a command-line flag): one line for the user, with what would
/// work where there is something.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum Refusal {
    /// The core refused a parameter of the top.
    #[error(transparent)]
    Param(#[from] spintop::physics::ParamError),
    /// A model does not take the method.
    #[error(transparent)]
    Method(#[from] spintop::sim::MethodRefused),
    /// The core refused the start (Ω₀) or could not build a simulation.
    #[error(transparent)]
    Sim(#[from] spintop::sim::SimError),
    /// A scene of the catalogue that is not a top scene.
    #[error("{0}")]
    Scene(String),
    /// A warp that is not one of [`super::settings::WARPS`].
    #[error("--warp must be one of {0} (tau per second)")]
    Warp(String),
    /// The models would need more steps a second than the view can take.
    #[error(
        "{what} needs {steps} steps a second at {warp} {unit}/s, the view takes {}; {cheaper}",
        spintop::numbers::fmt_budget(*limit)
    )]
    TooCostly {
        /// The costliest model and method.
        what: String,
        /// The steps a second, formatted (`about 4.0e7`).
        steps: String,
        /// The warp asked for.
        warp: Real,
        /// The unit of time.
        unit: &'static str,
        /// What would cost less.
        cheaper: String,
        /// The most steps a second the view takes.
        limit: Real,
    },
    /// A number typed into the Ω₀ field that is not one.
    #[error(transparent)]
    Entry(#[from] super::entry::EntryError),
    /// No method of the cycle can run this top live.
    #[error("no other method can run this top")]
    NoOtherMethod,
}

impl Refusal {
    /// The refusal as the command line says it: flags where the live view
    /// names keys (`--warp 50`, not "- slows down"; `--method exact`, not
    /// "m").
    pub fn on_command_line(&self) -> String {
        let text = self.to_string();
        match self {
            Refusal::TooCostly { cheaper, .. } => {
                let slower = cheaper
                    .strip_prefix("at ")
                    .and_then(|c| c.split_whitespace().next())
                    .map(str::to_string);
                let text = match slower {
                    Some(w) => text.replace("(- slows down)", &format!("(--warp {w})")),
                    None => text,
                };
                text.replace("closed forms (m)", "closed forms (--method exact)")
            }
            _ => text,
        }
    }
}
