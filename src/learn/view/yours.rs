//! The student's own function of time beside the scene it computes, drawn
//! against spintop's closed form: the probe's samples as the grader sees
//! them, and whether they agree.

use super::super::Learn;
use crate::term::theme;
use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Axis, Block, Chart, Dataset, GraphType, Paragraph};

/// Ω(t) of the probe's model by spintop's own closed form, the reference
/// the student's function is drawn against.
fn reference_omega(spec: &spintop_course::ProbeSpec, t: f64) -> [f64; 3] {
    use spintop::physics::symmetric_top::{self as sym, SymmetricTop};
    let Ok(top) = SymmetricTop::new(spec.ratio, spec.tau) else {
        return [f64::NAN; 3];
    };
    let w0 = spintop::math::Vec3::from(spec.omega0);
    let w = if spec.function == "truncated_closed_form" {
        sym::truncated_closed_form(&top, &w0, t)
    } else {
        sym::reduced_closed_form(&top, &w0, t)
    };
    [w.x, w.y, w.z]
}

/// Draws the student's function of time of this chapter, if sampled.
pub fn draw_yours(frame: &mut Frame, area: Rect, learn: &Learn) {
    use spintop_course::Probed;
    let Some((spec, probed)) = learn.yours() else {
        return;
    };
    let samples = match probed {
        Ok(Probed::Samples(s)) => s,
        Ok(Probed::Panicked(m)) => {
            let line = format!(" yours: {} panics: {m}", spec.function);
            frame.render_widget(Paragraph::new(Span::styled(line, theme::error())), area);
            return;
        }
        Err(e) => {
            let line = format!(" yours: {} could not be sampled: {e}", spec.function);
            frame.render_widget(Paragraph::new(Span::styled(line, theme::error())), area);
            return;
        }
    };
    let reference: Vec<(f64, [f64; 3])> = samples
        .iter()
        .map(|(t, _)| (*t, reference_omega(spec, *t)))
        .collect();
    let worst = samples
        .iter()
        .zip(&reference)
        .map(|((_, a), (_, b))| (0..3).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max))
        .fold(
            0.0,
            |m: f64, d| if d.is_nan() { f64::INFINITY } else { m.max(d) },
        );
    let scale = spec.omega0.iter().fold(0.0f64, |m, w| m.max(w.abs()));
    let agrees = worst <= 1e-9 * scale.max(1e-300);
    let curve = |data: &[(f64, [f64; 3])], i: usize| -> Vec<(f64, f64)> {
        data.iter().map(|(t, w)| (*t, w[i])).collect()
    };
    let series = [
        (curve(&reference, 0), theme::frame()),
        (curve(&reference, 1), theme::frame()),
        (curve(samples, 0), Style::new().fg(theme::OMEGA[0])),
        (curve(samples, 1), Style::new().fg(theme::OMEGA[1])),
    ];
    let datasets = series
        .iter()
        .map(|(data, style)| {
            Dataset::default()
                .marker(ratatui::symbols::Marker::Braille)
                .graph_type(GraphType::Line)
                .style(*style)
                .data(data)
        })
        .collect();
    let equation = if spec.function == "truncated_closed_form" {
        "(4.7)"
    } else {
        "(4.15)-(4.16)"
    };
    let verdict = if agrees {
        let worst = spintop::numbers::exponent(worst, 0);
        Span::styled(format!("agrees ✓ ({worst})"), theme::info())
    } else {
        let worst = spintop::numbers::exponent(worst, 1);
        Span::styled(format!("off by {worst} ✗"), theme::error())
    };
    let title = Line::from(vec![
        Span::styled(format!(" yours: {} ", spec.function), theme::title()),
        Span::styled("━Ω₁ ", Style::new().fg(theme::OMEGA[0])),
        Span::styled("━Ω₂ ", Style::new().fg(theme::OMEGA[1])),
        Span::styled(format!("vs {equation} grey │ "), theme::label()),
        verdict,
    ]);
    // Ω₁ and Ω₂ are drawn: they stay within Ω⊥₀.
    let perp = spec.omega0[0].hypot(spec.omega0[1]);
    let y = spintop::numbers::nice_ceiling(if perp > 0.0 { perp } else { scale } * 1.05);
    let chart = Chart::new(datasets)
        .block(Block::new().title(title))
        .legend_position(None)
        .x_axis(
            Axis::default()
                .style(theme::frame())
                .bounds([0.0, spec.t_end])
                .labels(["0".to_string(), format!("{:.0} t/τ", spec.t_end)]),
        )
        .y_axis(
            Axis::default()
                .style(theme::frame())
                .bounds([-y, y])
                .labels([format!("{}", -y), "0".into(), format!("{y}")]),
        );
    frame.render_widget(chart, area);
}
