//! `spintop tui` (and `spintop` with no arguments): the live view.
//!
//! Validates the starting parameters, refuses to start when stdout is not a
//! terminal (pointing at the text commands instead), and always restores the
//! terminal: on quit, on error, and on panic (`ratatui::init` installs a hook).

use super::{CliError, bad, parse_number, parse_vec3};
use crate::math::Real;
use crate::scene::{Body, Scene};
use crate::sim::{MethodChoice, Model};
use crate::tui::app::{App, Method, Settings, WARPS};
use crate::tui::event;
use clap::{Args, ValueEnum};
use std::io::{self, IsTerminal, Write};
use std::time::Duration;

/// A method of the live view and of `plot`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum ViewMethod {
    /// Closed forms (the reduced model's orientation by DOP853).
    Exact,
    /// Fixed-step classical RK4, step 0.01 tau.
    Rk4,
    /// Dormand-Prince 5(4), adaptive.
    Dopri5,
    /// DOP853, adaptive.
    Dop853,
    /// Radau IIA 5, implicit and L-stable, adaptive.
    Radau5,
}

impl From<ViewMethod> for Method {
    fn from(m: ViewMethod) -> Self {
        match m {
            ViewMethod::Exact => Method::ClosedForm,
            ViewMethod::Rk4 => Method::Rk4,
            ViewMethod::Dopri5 => Method::Dopri5,
            ViewMethod::Dop853 => Method::Dop853,
            ViewMethod::Radau5 => Method::Radau5,
        }
    }
}

/// The raw arguments of `tui`, before validation.
#[derive(Debug, Default, Args)]
pub struct TuiArgs {
    /// A top scene to open: a scene file, or a catalogue name (`spintop scenes`).
    #[arg(value_name = "SCENE", conflicts_with_all = ["ratio", "omega", "method"])]
    scene: Option<String>,
    /// I3/I1 of both models, in (0, 2] [default: 0.4]
    #[arg(long, value_parser = parse_number, allow_hyphen_values = true)]
    ratio: Option<Real>,
    /// Initial body angular velocity, in 1/tau [default: 0,0.1,0.2]
    #[arg(long, value_name = "W1,W2,W3", value_parser = parse_vec3, allow_hyphen_values = true)]
    omega: Option<[Real; 3]>,
    /// Numerical method of both models [default: exact]
    #[arg(long, value_enum)]
    method: Option<ViewMethod>,
    /// Model time per wall-clock second, in tau: 0.5, 1, 2, 5, 10, 20, 50, 100,
    /// 200, 500 or 1000 [default: 10]
    #[arg(long, value_parser = parse_number, allow_hyphen_values = true)]
    warp: Option<Real>,
    /// Benchmark: run for SECONDS, then print frames per second and CPU use.
    #[arg(long, value_name = "SECONDS", value_parser = parse_number, allow_hyphen_values = true)]
    bench: Option<Real>,
}

impl TuiArgs {
    fn settings(&self) -> Result<(Settings, Option<String>), CliError> {
        if let Some(arg) = &self.scene {
            let scene = super::run::load(arg)?;
            let (settings, note) = scene_settings(&scene, self.warp)?;
            return Ok((settings, Some(note)));
        }
        Settings::new(
            self.ratio.unwrap_or(0.4),
            self.omega.unwrap_or([0.0, 0.1, 0.2]),
            self.method.map_or(Method::ClosedForm, Method::from),
            self.warp.unwrap_or(WARPS[crate::tui::app::DEFAULT_WARP]),
        )
        .map(|s| (s, None))
        .map_err(bad)
    }
}

/// The live view's settings for a top scene, and the line it opens with.
///
/// The view runs in τ units, with the lab z axis along L₀. A truncated,
/// reduced or full scene opens the symmetric layout, the truncated and
/// reduced models side by side, with its I₃/I₁, Ω₀ and method. An asymmetric
/// (general) scene opens the general layout: one column, the truncated ALE
/// (3.3) with its moments and dipole, integrated by the scene's method
/// (DOP853 for `auto`, since nothing is closed). Scenes of other kinds are
/// refused.
pub fn scene_settings(scene: &Scene, warp: Option<Real>) -> Result<(Settings, String), CliError> {
    let Body::Top(top) = &scene.body else {
        // A catalogue scene is run by its name, which works from any folder;
        // its repository path would not.
        let runnable = match crate::scene::catalogue::find(&scene.name) {
            Some(entry) if entry.path() == scene.file => scene.name.clone(),
            _ => scene.file.clone(),
        };
        return Err(bad(format!(
            "{}: the live view opens top scenes, and this one is kind = \"{}\"; use `spintop run {runnable}`",
            scene.file,
            scene.kind().name(),
        )));
    };
    let warp = warp.unwrap_or(WARPS[crate::tui::app::DEFAULT_WARP]);
    let omega0 = top.initial.omega.into();
    let integrated = |closed: Method| match top.method {
        MethodChoice::Rk4 => Method::Rk4,
        MethodChoice::Dopri5 => Method::Dopri5,
        MethodChoice::Dop853 => Method::Dop853,
        MethodChoice::Radau5 => Method::Radau5,
        // NOTE: the live view steps a few model units per frame and offers
        // its own methods; a scene's taylor (or auto) opens on its default.
        MethodChoice::Auto | MethodChoice::Exact | MethodChoice::Forward | MethodChoice::Taylor => {
            closed
        }
    };
    let mut note = format!("scene {}", scene.name);
    let settings = match top.model {
        Model::General(general) | Model::GeneralReduced(general) | Model::GeneralFull(general) => {
            let method = integrated(Method::Dop853);
            if let Some(g) = &top.general_units {
                note.push_str(&format!(
                    ": a real particle, τ_f = {:.2e} s, far too slow to watch in these units; `spintop run {}` gives its secular drift",
                    g.fast_time_seconds(),
                    scene.name
                ));
            } else {
                note.push_str(&format!(
                    ": a general top under (3.3), the reduced ALE and the physical solution of (3.4) side by side, the first two integrated by {}; time in u, the unit where κ = 1",
                    method.name()
                ));
            }
            Settings::general(general, omega0, method, warp).map_err(bad)?
        }
        Model::Truncated(t) | Model::Reduced(t) | Model::Full(t) => {
            if let Some(u) = &top.units {
                note.push_str(&format!(
                    ": a real particle, τ = {:.2e} s, far too slow to watch in τ units; `spintop run {}` gives its times",
                    u.tau_seconds(),
                    scene.name
                ));
            } else if matches!(top.model, Model::Full(_)) {
                note.push_str(": the full ALE (3.4) is not in this view; both symmetric models run with its I₃/I₁ and Ω₀");
            } else {
                note.push_str(&format!(": {}", scene.summary()));
            }
            Settings::new(t.ratio(), omega0, integrated(Method::ClosedForm), warp).map_err(bad)?
        }
    };
    Ok((settings, note))
}

/// Restores the terminal when dropped, so that every way out of the loop
/// (quit, an I/O error, an early return) leaves the shell usable.
struct Restore;

impl Drop for Restore {
    fn drop(&mut self) {
        ratatui::restore();
    }
}

/// Validate, check for a terminal, run the live view, restore the terminal.
pub(crate) fn execute(args: TuiArgs, out: &mut impl Write) -> Result<(), CliError> {
    let (settings, note) = args.settings()?;
    let limit = match args.bench {
        Some(s) if !(s > 0.0 && s <= 3600.0) => {
            return Err(bad(format!("--bench takes 0 < SECONDS <= 3600, got {s}")));
        }
        s => s.map(Duration::from_secs_f64),
    };
    if !io::stdout().is_terminal() {
        return Err(bad(
            "the live view needs a terminal, but stdout is not one; for text output use \
             `spintop simulate` (numbers) or `spintop plot` (ASCII charts)",
        ));
    }
    crate::tui::signals::check_terminal_capable().map_err(|e| {
        bad(format!(
            "{e}; for text output use `spintop simulate` (numbers) or `spintop plot` (ASCII charts)"
        ))
    })?;
    let mut app = App::new(settings).map_err(bad)?;
    if let Some(note) = note {
        app = app.with_message(note);
    }
    let report = {
        let _restore = Restore;
        let mut terminal = ratatui::try_init()?;
        event::run(&mut terminal, &mut app, limit)?
    };
    if let Some(signal) = report.signal {
        return Err(CliError::Signal(signal, crate::tui::signals::name(signal)));
    }
    if limit.is_some() {
        let cpu = match (report.cpu, report.cpu_share()) {
            (Some(cpu), Some(share)) => format!(
                "CPU {:.2} s = {:.1}% of one core",
                cpu.as_secs_f64(),
                100.0 * share
            ),
            _ => "CPU time not available on this platform".into(),
        };
        writeln!(
            out,
            "spintop tui --bench: {} frames in {:.2} s = {:.1} fps; {cpu}; t = {:.1}τ at {} τ/s",
            report.frames,
            report.wall.as_secs_f64(),
            report.fps(),
            app.time(),
            app.settings().warp(),
        )?;
    }
    Ok(())
}
