//! Reading the keys of a scene file: each number finite and in range, each
//! name one of those offered, each key in its own section, and every refusal
//! a [`SceneError`] that points at the line it came from. Also the output
//! times of `[solve]`, which every kind reads the same way.

use super::SceneError;
use super::format::{Key, RawSolve};
use crate::math::Real;
use crate::numbers::fmt_value;
use crate::physics::ParamError;
use crate::sim::MethodChoice;
use crate::sim::times::{MAX_SAMPLES, check_times, even_times};
use std::ops::Range;
use toml::Spanned;

/// A value that was given, with the byte range it came from.
pub(super) type At<T> = Option<(T, Range<usize>)>;

/// The file name and text, to turn byte offsets into lines.
pub(super) struct Ctx<'a> {
    pub(super) file: &'a str,
    pub(super) text: &'a str,
}

impl Ctx<'_> {
    pub(super) fn line(&self, offset: usize) -> usize {
        let end = offset.min(self.text.len());
        1 + self.text.as_bytes()[..end]
            .iter()
            .filter(|b| **b == b'\n')
            .count()
    }

    pub(super) fn at(&self, span: &Range<usize>, message: impl Into<String>) -> SceneError {
        SceneError {
            file: self.file.to_string(),
            line: self.line(span.start),
            message: message.into(),
        }
    }
}

/// A plain number key: finite, or refused with the key and what it expects.
pub(super) fn num(
    ctx: &Ctx,
    section: &str,
    key: &str,
    v: &Key<Real>,
    expected: &str,
) -> Result<At<Real>, SceneError> {
    let Some(v) = v else { return Ok(None) };
    let x = *v.get_ref();
    if !x.is_finite() {
        return Err(ctx.at(
            &v.span(),
            format!(
                "[{section}] {key} = {} is not a finite number; expected {expected}",
                fmt_value(x)
            ),
        ));
    }
    Ok(Some((x, v.span())))
}

/// A number key that must satisfy `ok`.
pub(super) fn num_in(
    ctx: &Ctx,
    section: &str,
    key: &str,
    v: &Key<Real>,
    ok: impl Fn(Real) -> bool,
    expected: &str,
) -> Result<At<Real>, SceneError> {
    let got = num(ctx, section, key, v, expected)?;
    if let Some((x, span)) = &got
        && !ok(*x)
    {
        return Err(ctx.at(
            span,
            format!(
                "[{section}] {key} = {} is out of range; expected {expected}",
                fmt_value(*x)
            ),
        ));
    }
    Ok(got)
}

/// An array key whose entries must all be finite.
pub(super) fn finite_array<const N: usize>(
    ctx: &Ctx,
    section: &str,
    key: &str,
    v: &Key<[Real; N]>,
    expected: &str,
) -> Result<At<[Real; N]>, SceneError> {
    let Some(v) = v else { return Ok(None) };
    let a = *v.get_ref();
    if let Some(x) = a.iter().find(|x| !x.is_finite()) {
        return Err(ctx.at(
            &v.span(),
            format!("[{section}] {key} holds {x}, not a finite number; expected {expected}"),
        ));
    }
    Ok(Some((a, v.span())))
}

/// A string key that must be one of `options`; returns its index.
pub(super) fn choice(
    ctx: &Ctx,
    section: &str,
    key: &str,
    v: &Key<String>,
    options: &[&str],
) -> Result<At<usize>, SceneError> {
    let Some(v) = v else { return Ok(None) };
    let s = v.get_ref();
    match options.iter().position(|o| o == s) {
        Some(i) => Ok(Some((i, v.span()))),
        None => Err(ctx.at(
            &v.span(),
            format!(
                "[{section}] {key} = \"{s}\" is not known; expected one of {}",
                options.join(", ")
            ),
        )),
    }
}

pub(super) fn missing(
    ctx: &Ctx,
    header: &Range<usize>,
    section: &str,
    key: &str,
    expected: &str,
) -> SceneError {
    ctx.at(
        header,
        format!("[{section}] is missing the key {key}; expected {expected}"),
    )
}

/// A key given where it does not belong.
pub(super) fn not_here<T>(
    ctx: &Ctx,
    v: &Key<T>,
    section: &str,
    key: &str,
    why: &str,
) -> Result<(), SceneError> {
    match v {
        Some(v) => Err(ctx.at(&v.span(), format!("[{section}] {key} {why}"))),
        None => Ok(()),
    }
}

/// Point a refused physical parameter at the key it came from.
pub(super) fn param(
    ctx: &Ctx,
    e: ParamError,
    spans: &[(&str, Option<&Range<usize>>)],
    fallback: &Range<usize>,
    section: &str,
) -> SceneError {
    let name = match &e {
        ParamError::NotFinite { name, .. } | ParamError::OutOfRange { name, .. } => *name,
        ParamError::RatioOutOfRange(_) => "I3/I1",
        ParamError::MomentNotPositive { .. } | ParamError::TriangleInequality(..) => "inertia",
        ParamError::ZeroDipole => "dipole",
        ParamError::NegativeTau(_) => "tau",
    };
    let found = spans
        .iter()
        .find(|(n, _)| *n == name || name.starts_with(n))
        .and_then(|(n, s)| s.map(|s| (n, s)));
    match found {
        Some((_, span)) => ctx.at(span, format!("[{section}] {e}")),
        None => ctx.at(fallback, format!("[{section}] {e}")),
    }
}

/// The bare key that a `key = value` line holding byte `offset` assigns.
pub(super) fn key_on_line(text: &str, offset: usize) -> Option<&str> {
    let offset = offset.min(text.len());
    let start = text[..offset].rfind('\n').map_or(0, |i| i + 1);
    let line = &text[start..];
    let (key, _) = line.split_once('=')?;
    let key = key.trim();
    let bare = !key.is_empty()
        && key
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    bare.then_some(key)
}

/// The output times of `[solve]`: `times`, or `t_end` with `samples` evenly
/// spaced from 0, scaled by `scale` (τ per time unit). Returns the times and
/// the span to point at in later complaints.
pub(super) fn solve_times(
    ctx: &Ctx,
    solve: Option<(&RawSolve, Range<usize>)>,
    section: &Range<usize>,
    default: Option<(Real, usize)>,
    any_order: bool,
    scale: Real,
) -> Result<(Vec<Real>, Option<Range<usize>>), SceneError> {
    let none = RawSolve {
        method: None,
        rtol: None,
        step: None,
        times: None,
        t_end: None,
        samples: None,
    };
    let (s, header) = match &solve {
        Some((s, span)) => (*s, span.clone()),
        None => (&none, section.clone()),
    };
    let t_end_or_samples = s
        .t_end
        .as_ref()
        .map(Spanned::span)
        .or(s.samples.as_ref().map(Spanned::span));
    if s.times.is_some()
        && let Some(other) = t_end_or_samples
    {
        return Err(ctx.at(
            &other,
            "[solve] gives both times and t_end/samples; expected either times = [...] or t_end (with samples)",
        ));
    }
    if let Some(times) = &s.times {
        let list = times.get_ref();
        let span = times.span();
        check_times(list, !any_order).map_err(|e| {
            let expected = if any_order {
                "finite numbers"
            } else {
                "finite times >= 0, in increasing order"
            };
            ctx.at(&span, format!("[solve] {e}; expected {expected}"))
        })?;
        let scaled: Vec<Real> = list.iter().map(|t| t * scale).collect();
        if scaled.iter().any(|t| !t.is_finite()) {
            return Err(ctx.at(
                &span,
                "[solve] times overflow when converted to units of tau; expected shorter times",
            ));
        }
        return Ok((scaled, Some(span)));
    }
    let t_end = num_in(ctx, "solve", "t_end", &s.t_end, |t| t >= 0.0, "a time >= 0")?;
    let samples = match &s.samples {
        Some(n) => {
            let v = *n.get_ref();
            if !(1..=MAX_SAMPLES as i64).contains(&v) {
                return Err(ctx.at(
                    &n.span(),
                    format!("[solve] samples = {v} is out of range; expected 1 to {MAX_SAMPLES}"),
                ));
            }
            Some(v as usize)
        }
        None => None,
    };
    let (t_end, span, n) = match (t_end, default) {
        (Some((t, span)), d) => (t, Some(span), samples.unwrap_or(d.map_or(11, |d| d.1))),
        (None, Some((t, n))) => {
            if let Some(sp) = &s.samples {
                return Err(ctx.at(
                    &sp.span(),
                    "[solve] samples needs t_end; expected t_end = ... beside it",
                ));
            }
            (t, None, samples.unwrap_or(n))
        }
        (None, None) => {
            return Err(ctx.at(
                &header,
                "[solve] gives no output times; expected times = [...] or t_end = ... (with samples)",
            ));
        }
    };
    let t_end = t_end * scale;
    if !t_end.is_finite() {
        return Err(ctx.at(
            &header,
            "[solve] t_end overflows when converted to units of tau; expected a shorter time",
        ));
    }
    Ok((even_times(t_end, n), span))
}

/// Refuse `method`, `rtol` and `step` where the kind fixes its own method.
pub(super) fn fixed_method(
    ctx: &Ctx,
    solve: Option<(&RawSolve, Range<usize>)>,
    kind: &str,
    why: &str,
    rtol_ok: bool,
) -> Result<(), SceneError> {
    let Some((s, _)) = solve else { return Ok(()) };
    if let Some((m, span)) = choice(ctx, "solve", "method", &s.method, &MethodChoice::NAMES)?
        && m != 0
    {
        return Err(ctx.at(
            &span,
            format!("[solve] method = \"{}\" does not apply to kind = \"{kind}\" ({why}); expected auto", MethodChoice::NAMES[m]),
        ));
    }
    not_here(
        ctx,
        &s.step,
        "solve",
        "step",
        &format!(
            "does not apply to kind = \"{kind}\"; it sets the fixed step of method = \"rk4\" for a top"
        ),
    )?;
    if !rtol_ok {
        not_here(
            ctx,
            &s.rtol,
            "solve",
            "rtol",
            &format!("does not apply to kind = \"{kind}\" ({why})"),
        )?;
    }
    Ok(())
}
