//! `spintop plot`: the curves of the live view as text charts on stdout, for
//! pipes and for the book.
//!
//! One chart per quantity (Ω₁, Ω₂, Ω₃, Ω⊥) and per model, drawn by textplots
//! in Braille dots, with the same parameters, initial orientation (lab z along
//! L₀) and y ranges as the live view.

use super::gate::Gate;
use super::{CliError, bad, parse_number, parse_vec3};
use clap::{Args, ValueEnum};
use spintop::math::{Real, Vec3};
use spintop::numbers::{fmt_axis, nice_ceiling};
use spintop::physics::rigid_body::lab_frame;
use spintop::physics::symmetric_top::SymmetricTop;
use spintop::sim::{
    InitialState, MethodChoice, MethodOptions, Model, Sample, SimError, Simulation,
};
use std::io::Write;
use textplots::{AxisBuilder, Chart, LabelBuilder, LabelFormat, LineStyle, Plot, Shape};

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum PlotModel {
    /// Eqs. (4.2)-(4.4): no Schott term.
    Truncated,
    /// Eqs. (4.12)-(4.14): Schott term kept, reduced.
    Reduced,
    /// Both, truncated first.
    Both,
}

/// The raw arguments of `plot`, before validation.
#[derive(Debug, Args)]
#[command(after_help = "Examples:\n  \
    spintop plot --model both --t-end 500\n  \
    spintop plot --model reduced --log-time --t-end 1e4 --width 100")]
pub struct PlotArgs {
    /// Which model(s) to plot.
    #[arg(long, value_enum, default_value = "both")]
    model: PlotModel,
    /// I3/I1, in (0, 2].
    #[arg(long, value_parser = parse_number, allow_hyphen_values = true, default_value = "0.4")]
    ratio: Real,
    /// Initial body angular velocity, in 1/tau.
    #[arg(long, value_name = "W1,W2,W3", value_parser = parse_vec3, allow_hyphen_values = true,
          default_value = "0,0.1,0.2")]
    omega: [Real; 3],
    /// Last time of the plot, in tau.
    #[arg(long, value_parser = parse_number, allow_hyphen_values = true, default_value = "500")]
    t_end: Real,
    /// Plot against log10 t over the four decades that end at --t-end.
    #[arg(long)]
    log_time: bool,
    /// Numerical method.
    #[arg(long, value_parser = super::values::method(), default_value = "exact")]
    method: MethodChoice,
    /// Width of each chart, in characters (16 to 500).
    #[arg(long, default_value_t = 60, value_parser = spintop::numbers::parse_count::<u32>, allow_hyphen_values = true)]
    width: u32,
    /// Height of each chart, in lines (2 to 200).
    #[arg(long, default_value_t = 10, value_parser = spintop::numbers::parse_count::<u32>, allow_hyphen_values = true)]
    height: u32,
}

/// A validated `plot` request.
struct PlotConfig {
    /// The symmetric top every plotted model shares.
    top: SymmetricTop,
    models: Vec<Model>,
    omega0: [Real; 3],
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
        "{flag}: plot draws in single precision, so {what} within {:.0e} and {:.0e}, got {}; {instead}",
        PLOT_RANGE.0,
        PLOT_RANGE.1,
        spintop::numbers::fmt_value(value)
    )))
}

/// The decades a log-time plot spans.
const LOG_DECADES: Real = 4.0;

impl PlotArgs {
    fn validate(self) -> Result<PlotConfig, CliError> {
        let top = SymmetricTop::new(self.ratio, 1.0).map_err(SimError::from)?;
        InitialState::new(
            Vec3::from(self.omega),
            lab_frame(&top.inertia(), &Vec3::from(self.omega)),
        )?;
        // parse_number has already refused NaN and infinities.
        if self.t_end <= 0.0 {
            return Err(bad(format!(
                "--t-end must be > 0, got {}",
                spintop::numbers::fmt_value(self.t_end)
            )));
        }
        // NOTE: textplots draws in single precision: a curve beyond its
        // range drew as inf (exit 3 after the header) or flat at 0, and so
        // did a linear time axis (a log-time axis draws log10 t, which
        // always fits).
        let [w1, w2, w3] = self.omega;
        let reach = w1.hypot(w2).max(w3.abs());
        if !self.log_time {
            drawable(
                self.t_end,
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
        if !(16..=500).contains(&self.width) {
            return Err(bad(format!(
                "--width must be 16 to 500 characters, got {}",
                self.width
            )));
        }
        if !(2..=200).contains(&self.height) {
            return Err(bad(format!(
                "--height must be 2 to 200 lines, got {}",
                self.height
            )));
        }
        let models = match self.model {
            PlotModel::Truncated => vec![Model::Truncated(top)],
            PlotModel::Reduced => vec![Model::Reduced(top)],
            PlotModel::Both => vec![Model::Truncated(top), Model::Reduced(top)],
        };
        for model in &models {
            model
                .check_method(self.method)
                .map_err(|e| bad(format!("--method {}: {e}", self.method.name())))?;
        }
        // NOTE: two samples per Braille dot column, so lines join smoothly.
        let n = 4 * self.width as usize;
        let times = (0..=n)
            .map(|i| {
                let f = i as Real / n as Real;
                if self.log_time {
                    self.t_end * (10.0 as Real).powf(LOG_DECADES * (f - 1.0))
                } else {
                    self.t_end * f
                }
            })
            .collect();
        Ok(PlotConfig {
            top,
            models,
            omega0: self.omega,
            method: self.method,
            times,
            log_time: self.log_time,
            width: self.width,
            height: self.height,
            t_end: self.t_end,
            reach,
        })
    }
}

/// A curve's name and how to read it from a sample.
type Quantity = (&'static str, fn(&Sample) -> Real);

/// Run one model at the plot's times.
fn samples(
    config: &PlotConfig,
    model: Model,
    top: &SymmetricTop,
) -> Result<(Vec<Sample>, &'static str), CliError> {
    let mut initial = InitialState::new(
        Vec3::from(config.omega0),
        lab_frame(&top.inertia(), &Vec3::from(config.omega0)),
    )?;
    initial.rotation = lab_frame(&top.inertia(), &Vec3::from(config.omega0)).to_rotation();
    let horizon = config.times.last().copied();
    let choice = config.method;
    let failure = |e| super::sim_failure(e, &model, choice);
    let mut sim = Simulation::new(model, choice, MethodOptions::default(), initial, horizon)
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
        .map(|model| samples(config, *model, &config.top))
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
