//! `spintop plot`: the curves of the live view as text charts on stdout, for
//! pipes and for the book.
//!
//! One chart per quantity (Ω₁, Ω₂, Ω₃, Ω⊥) and per model, drawn by textplots
//! in Braille dots, with the same parameters, initial orientation (lab z along
//! L₀) and y ranges as the live view.

use super::gate::Gate;
use super::values::{self, help, value_name};
use super::{CliError, bad};
use clap::Args;
use clap::builder::{PossibleValue, PossibleValuesParser};
use spintop::math::Real;
use spintop::numbers::{fmt_axis, nice_ceiling};
use spintop::physics::symmetric_top::SymmetricTop;
use spintop::scene::request::{self, Given, RawSolve, RawTop};
use spintop::scene::table::{self, Choice, Command, MODELS, ModelAsk, Tier};
use spintop::sim::{MethodChoice, MethodOptions, Model, Sample, Simulation};
use std::io::Write;
use textplots::{AxisBuilder, Chart, LabelBuilder, LabelFormat, LineStyle, Plot, Shape};

/// `--model`: the symmetric top's models with a closed form, from the core's
/// table, and `both`.
fn plot_models() -> PossibleValuesParser {
    let mut names: Vec<PossibleValue> = closed_models()
        .map(|c| PossibleValue::new(c.name).help(c.help))
        .collect();
    names.push(PossibleValue::new(BOTH).help("Both, truncated first"));
    PossibleValuesParser::new(names)
}

/// The names of the core's table a plot takes: the symmetric top's models
/// with a closed form, lightest first (what `both` plots).
fn closed_models() -> impl Iterator<Item = &'static Choice<ModelAsk>> {
    let closed = |tier| matches!(tier, Some(Tier::Truncated | Tier::Reduced));
    MODELS
        .iter()
        .filter(move |c| !c.value.asymmetric && closed(c.value.tier))
}

/// The `--model` that plots the truncated and the reduced model.
const BOTH: &str = "both";

const S: Command = Command::Simulate;
const P: Command = Command::Plot;

/// The raw arguments of `plot`, before validation: the keys of a top scene's
/// `[top]` and `[solve]` (lab z along L0), and the chart's own.
#[derive(Debug, Args)]
#[command(after_help = "Examples:\n  \
    spintop plot --model both --t-end 500\n  \
    spintop plot --model reduced --log-time --t-end 1e4 --width 100")]
pub struct PlotArgs {
    /// Which model(s) to plot.
    #[arg(long, value_parser = plot_models(), default_value = BOTH)]
    model: String,
    #[arg(long, value_parser = values::real, allow_hyphen_values = true,
          value_name = value_name(S, "top", "ratio"), help = help(S, "top", "ratio"))]
    ratio: Option<Real>,
    #[arg(long, value_parser = values::array::<3>, allow_hyphen_values = true,
          value_name = value_name(S, "top", "omega"), help = help(S, "top", "omega"))]
    omega: Option<[Real; 3]>,
    #[arg(long, value_parser = values::real, allow_hyphen_values = true,
          value_name = value_name(P, "plot", "t_end"), help = help(P, "plot", "t_end"))]
    t_end: Option<Real>,
    /// Plot against log10 t over the four decades that end at --t-end.
    #[arg(long)]
    log_time: bool,
    #[arg(long, value_parser = values::method_name_of(P, "solve", "method"),
          help = help(P, "solve", "method"))]
    method: Option<String>,
    #[arg(long, value_parser = values::whole, allow_hyphen_values = true,
          value_name = value_name(P, "plot", "width"), help = help(P, "plot", "width"))]
    width: Option<i64>,
    #[arg(long, value_parser = values::whole, allow_hyphen_values = true,
          value_name = value_name(P, "plot", "height"), help = help(P, "plot", "height"))]
    height: Option<i64>,
}

/// A validated `plot` request.
struct PlotConfig {
    /// The symmetric top every plotted model shares.
    top: SymmetricTop,
    models: Vec<Model>,
    omega0: [Real; 3],
    /// Ω₀ and O(0), lab z along L₀.
    initial: spintop::sim::InitialState,
    method: MethodChoice,
    times: Vec<Real>,
    log_time: bool,
    width: u32,
    height: u32,
    t_end: Real,
    /// The largest size a curve of Ω reaches, max(|Ω⊥₀|, |Ω₃₀|): neither
    /// model's Ω⊥ grows and Ω₃ stays, so it sets the charts' y range.
    reach: Real,
}

/// The sizes of omega0 a chart draws faithfully (textplots works in f32,
/// whose range is about 1e-38 to 3e38).
const PLOT_RANGE: (Real, Real) = (1e-30, 1e30);

/// Refuse `value` (of `flag`) outside what a single-precision chart draws
/// faithfully, [`PLOT_RANGE`].
fn drawable(value: Real, flag: &str, what: &str, instead: &str) -> Result<(), CliError> {
    if (PLOT_RANGE.0..=PLOT_RANGE.1).contains(&value) {
        return Ok(());
    }
    Err(bad(format!(
        "{flag}: plot draws in single precision, so {what} within {} and {}, got {}; {instead}",
        spintop::numbers::fmt_value(PLOT_RANGE.0),
        spintop::numbers::fmt_value(PLOT_RANGE.1),
        spintop::numbers::fmt_value(value)
    )))
}

/// The decades a log-time plot spans.
const LOG_DECADES: Real = 4.0;

/// The table's default of a key of `plot`.
fn plot_default(key: &str) -> table::DefaultValue {
    table::key(P, "plot", key).default
}

impl PlotArgs {
    /// The keys of `[top]` and `[solve]` the flags fill, for model `model`.
    fn keys(&self, model: &str, t_end: Real) -> (RawTop, RawSolve) {
        let top = RawTop {
            model: Some(Given::flag(model.to_string())),
            ratio: self.ratio.map(Given::flag),
            omega: self.omega.map(Given::flag),
            frame: Some(Given::flag("paper".to_string())),
            ..RawTop::default()
        };
        let method = self
            .method
            .clone()
            .or_else(|| table::key(P, "solve", "method").default.text());
        let solve = RawSolve {
            method: method.map(Given::flag),
            t_end: Some(Given::flag(t_end)),
            samples: Some(Given::flag(1)),
            ..RawSolve::default()
        };
        (top, solve)
    }

    fn validate(self) -> Result<PlotConfig, CliError> {
        let t_end = self
            .t_end
            .or(plot_default("t_end").number())
            .unwrap_or(table::PLOT_T_END);
        // A chart's last time against its own row of the table (> 0), before
        // the top's keys read it as `[solve] t_end`.
        let t_end = request::checked_number(P, "plot", "t_end", t_end)?;
        // Each model plotted is asked as a top scene would ask it.
        let names: Vec<&str> = if self.model == BOTH {
            closed_models().map(|c| c.name).collect()
        } else {
            vec![self.model.as_str()]
        };
        let mut requests = Vec::new();
        for name in names {
            let (top, solve) = self.keys(name, t_end);
            requests.push(request::top(&top, &solve)?);
        }
        let first = &requests[0];
        let count = |key: &str, given: Option<i64>| -> Result<u32, CliError> {
            let n = match (given, plot_default(key)) {
                (Some(n), _) => n,
                (None, table::DefaultValue::Count(n)) => n as i64,
                (None, _) => 0,
            };
            let n = request::checked_count(P, "plot", key, n)?;
            Ok(u32::try_from(n).unwrap_or(u32::MAX))
        };
        let (width, height) = (count("width", self.width)?, count("height", self.height)?);
        let omega0: [Real; 3] = first.initial.omega.into();
        // NOTE: textplots draws in single precision: a curve beyond its
        // range drew as inf (exit 3 after the header) or flat at 0, and so
        // did a linear time axis (a log-time axis draws log10 t, which
        // always fits).
        let [w1, w2, w3] = omega0;
        let reach = w1.hypot(w2).max(w3.abs());
        if !self.log_time {
            drawable(
                t_end,
                "--t-end",
                "a linear time axis must end",
                "use --log-time, or spintop simulate for the numbers",
            )?;
        }
        if reach != 0.0 {
            drawable(
                reach,
                "--omega",
                "the size of omega0 must lie",
                "spintop simulate gives the numbers at any size",
            )?;
        }
        let Model::Truncated(top) = first.tiers[0] else {
            return Err(bad("plot draws the symmetric top"));
        };
        let models = requests.iter().filter_map(|r| r.model()).collect();
        // NOTE: two samples per Braille dot column, so lines join smoothly.
        let n = 4 * width as usize;
        let times = (0..=n)
            .map(|i| {
                let f = i as Real / n as Real;
                if self.log_time {
                    t_end * (10.0 as Real).powf(LOG_DECADES * (f - 1.0))
                } else {
                    t_end * f
                }
            })
            .collect();
        Ok(PlotConfig {
            top,
            models,
            omega0,
            initial: first.initial,
            method: first.method,
            times,
            log_time: self.log_time,
            width,
            height,
            t_end,
            reach,
        })
    }
}

/// A curve's name and how to read it from a sample.
type Quantity = (&'static str, fn(&Sample) -> Real);

/// Run one model at the plot's times.
fn samples(config: &PlotConfig, model: Model) -> Result<(Vec<Sample>, &'static str), CliError> {
    let horizon = config.times.last().copied();
    let choice = config.method;
    let failure = |e| super::sim_failure(e, &model, choice);
    let mut sim = Simulation::new(
        model,
        choice,
        MethodOptions::default(),
        config.initial,
        horizon,
    )
    .map_err(failure)?;
    let samples = sim.run(&config.times).map_err(failure)?;
    Ok((samples, sim.method().label()))
}

fn write_plots(config: &PlotConfig, out: &mut impl Write) -> Result<(), CliError> {
    use spintop::numbers::short;
    let [w1, w2, w3] = config.omega0;
    let y = nice_ceiling(config.reach * 1.05) as f32;
    // Every model runs before anything is written: a refusal or a failure
    // leaves no half-printed chart behind.
    let runs = config
        .models
        .iter()
        .map(|model| samples(config, *model))
        .collect::<Result<Vec<_>, _>>()?;
    for (model, (samples, method)) in config.models.iter().zip(runs) {
        let top = &config.top;
        writeln!(
            out,
            "# spintop plot: {} model, {}; I3/I1 = {}, tau = 1; omega0 = ({}, {}, {}) 1/tau; \
             method {method}; lab z along L0",
            model.name(),
            model.equations(),
            short(top.ratio()),
            short(w1),
            short(w2),
            short(w3),
        )?;
        let quantities: [Quantity; 4] = [
            ("Ω₁", |s| s.omega[0]),
            ("Ω₂", |s| s.omega[1]),
            ("Ω₃", |s| s.omega[2]),
            ("Ω⊥", |s| s.omega_perp),
        ];
        for (name, value) in quantities {
            let points: Vec<(f32, f32)> = samples
                .iter()
                .map(|s| {
                    let x = if config.log_time { s.t.log10() } else { s.t };
                    (x as f32, value(s) as f32)
                })
                .collect();
            let (x_axis, x0, x1) = if config.log_time {
                let hi = config.t_end.log10();
                ("log t", hi - LOG_DECADES, hi)
            } else {
                ("t", 0.0, config.t_end)
            };
            writeln!(
                out,
                "\n{name}(t) of the {} model, in 1/tau, against {x_axis} (t in tau)",
                model.name()
            )?;
            let shape = Shape::Lines(&points);
            let mut chart = Chart::new_with_y_range(
                2 * config.width,
                4 * config.height,
                x0 as f32,
                x1 as f32,
                -y,
                y,
            );
            let log_time = config.log_time;
            // NOTE: textplots marks x = 0 with a dotted line; on a log₁₀ t
            // axis that is t = 1, which means nothing here.
            let y_axis = if log_time {
                LineStyle::None
            } else {
                LineStyle::Dotted
            };
            let chart = chart
                .y_axis_style(y_axis)
                .x_label_format(LabelFormat::Custom(Box::new(move |x| {
                    let x = Real::from(x);
                    fmt_axis(if log_time { (10.0 as Real).powf(x) } else { x })
                })))
                .y_label_format(LabelFormat::Custom(Box::new(|v| fmt_axis(Real::from(v)))))
                .lineplot(&shape);
            chart.axis();
            chart.figures();
            write!(out, "{chart}")?;
        }
        writeln!(out)?;
    }
    Ok(())
}

/// Validate, run and print `plot`.
pub(crate) fn execute(args: PlotArgs, out: &mut Gate<'_>) -> Result<(), CliError> {
    let config = args.validate()?;
    write_plots(&config, out)
}
