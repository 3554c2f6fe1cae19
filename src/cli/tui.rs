//! `spintop tui` (and `spintop` with no arguments): the live view.
//!
//! Validates the starting parameters, refuses to start when stdout is not a
//! terminal (pointing at the text commands instead), and runs the view
//! ([`crate::tui::run`]), which always restores the terminal.

use super::gate::Gate;
use super::values;
use super::{CliError, bad, parse_number};
use crate::live::settings::{DEFAULT_WARP, WARPS};
use crate::live::{App, Settings};
use crate::term::session;
use clap::Args;
use spintop::math::Real;
use spintop::numbers::{fmt_time, significant};
use spintop::scene::request::{self, Given, RawSolve, RawTop};
use spintop::scene::table::Command::{Plot as P, Simulate as S};
use spintop::sim::{MethodChoice, Model};
use std::io::Write;
use std::time::Duration;

/// The raw arguments of `tui`, before validation.
#[derive(Debug, Default, Args)]
#[command(after_help = "Examples:\n  \
    spintop tui                                      the paper's Figures 1 and 2, side by side\n  \
    spintop tui asymmetric-top                       a catalogue scene (`spintop scenes` lists them)\n  \
    spintop tui --ratio 1.5 --method dop853 --warp 100")]
pub struct TuiArgs {
    /// A top scene to open: a scene file, or a catalogue name (`spintop scenes`).
    #[arg(value_name = "SCENE", conflicts_with_all = ["ratio", "omega", "method"])]
    scene: Option<String>,
    #[arg(long, value_parser = values::real, allow_hyphen_values = true,
          value_name = values::value_name(S, "top", "ratio"), help = values::help(S, "top", "ratio"))]
    ratio: Option<Real>,
    #[arg(long, value_parser = values::array::<3>, allow_hyphen_values = true,
          value_name = values::value_name(S, "top", "omega"), help = values::help(S, "top", "omega"))]
    omega: Option<[Real; 3]>,
    #[arg(long, value_parser = values::method(P), help = values::help(P, "solve", "method"))]
    method: Option<MethodChoice>,
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
            let (settings, note) =
                Settings::for_scene(&scene, self.warp).map_err(|e| bad(e.on_command_line()))?;
            return Ok((settings, Some(note)));
        }
        let (ratio, omega0, method) = self.top()?;
        Settings::new(
            ratio,
            omega0,
            method,
            self.warp.unwrap_or(WARPS[DEFAULT_WARP]),
        )
        .map(|s| (s, None))
        .map_err(|e| bad(e.on_command_line()))
    }

    /// `--ratio`, `--omega` and `--method` read as `simulate` reads them (the
    /// keys of a `[top]` scene, by the core's one validation, with its
    /// defaults and in its words): I₃/I₁, Ω₀ and the method of the
    /// truncated model (the reduced one takes the same methods).
    fn top(&self) -> Result<(Real, [Real; 3], MethodChoice), CliError> {
        let method = self.method.unwrap_or(MethodChoice::Exact);
        let top = RawTop {
            model: Some(Given::flag("truncated".to_string())),
            ratio: self.ratio.map(Given::flag),
            omega: self.omega.map(Given::flag),
            ..RawTop::default()
        };
        let solve = RawSolve {
            method: Some(Given::flag(method.name().to_string())),
            ..RawSolve::default()
        };
        let request = request::top(&top, &solve)?;
        let Model::Truncated(top) = request.tiers[0] else {
            return Err(bad("the live view's flags ask for a symmetric top"));
        };
        Ok((top.ratio(), request.initial.omega.into(), request.method))
    }
}

/// Validate, check for a terminal, run the live view, restore the terminal.
pub(crate) fn execute(args: TuiArgs, out: &mut Gate<'_>) -> Result<(), CliError> {
    let (settings, note) = args.settings()?;
    let limit = match args.bench {
        Some(s) if !(s > 0.0 && s <= 3600.0) => {
            return Err(bad(format!(
                "--bench takes 0 < SECONDS <= 3600, got {}",
                spintop::numbers::fmt_value(s)
            )));
        }
        s => s.map(Duration::from_secs_f64),
    };
    session::check().map_err(|e| {
        bad(format!(
            "the live view {e}; for text output use \
             `spintop simulate` (numbers) or `spintop plot` (ASCII charts)"
        ))
    })?;
    let mut app = App::new(settings)
        .map_err(|e| bad(e.to_string()))?
        .in_background()
        .monochrome(crate::term::theme::no_color());
    if let Some(note) = note {
        app = app.with_message(note);
    }
    let report = crate::tui::run(&mut app, limit)?;
    if let Some(signal) = report.signal {
        return Err(CliError::Signal(signal, crate::term::signals::name(signal)));
    }
    if limit.is_some() {
        let cpu = match (report.cpu, report.cpu_share()) {
            (Some(cpu), Some(share)) => format!(
                "CPU {} s = {}% of one core",
                significant(cpu.as_secs_f64()),
                significant(100.0 * share)
            ),
            _ => "CPU time not available on this platform".into(),
        };
        writeln!(
            out,
            "spintop tui --bench: {} frames in {} s = {} fps; {cpu}; t = {}τ at {} τ/s",
            report.frames,
            significant(report.wall.as_secs_f64()),
            significant(report.fps()),
            fmt_time(app.time()),
            app.settings().warp(),
        )?;
    }
    Ok(())
}
