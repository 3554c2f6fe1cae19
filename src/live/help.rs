//! What the live view's help says: the keys, what each panel draws and what
//! every row of numbers means, for the top shown. The help scrolls
//! ([`crate::term::popup`]), so nothing is left out on a small terminal.

use super::layout::Top;
use crate::term::theme;
use ratatui::text::{Line, Span};

/// The help's width in columns (at most; a narrower terminal wraps it).
pub const HELP_WIDTH: u16 = 78;

/// The keys and what they do.
const KEYS: [(&str, &str); 13] = [
    ("space", "pause / resume"),
    (". or →", "one step of Δt while paused"),
    ("+ / -", "time warp (τ per wall-clock second)"),
    ("r", "restart both models at t = 0"),
    (
        "[ / ]",
        "I₃/I₁ down / up by 0.1 (a rigid body has 0 < I₃/I₁ ≤ 2)",
    ),
    ("↑ / ↓", "select a component of Ω₀"),
    (
        "Enter",
        "edit it: type or paste a number, ↑/↓ ±0.01, ^U clears, Enter applies, Esc cancels (q is refused there, never quits)",
    ),
    ("m", "method: {cycle}, and back to auto"),
    ("l", "log-time charts (the whole run) or the last 200τ"),
    (
        "Tab",
        "the next model, where the screen is too narrow for all of them",
    ),
    (
        "?",
        "this help: ↑ ↓ j k PgUp PgDn scroll it, any other key (q, Esc) closes",
    ),
    ("^L", "draw the whole screen again"),
    ("q ^C", "quit (Esc never quits: it closes or cancels)"),
];

/// What the help says instead for a general top.
const GENERAL_KEYS: [(&str, &str); 5] = [
    (
        "+ / -",
        "time warp (u per wall-clock second; u: the time unit where κ = 1)",
    ),
    ("l", "log-time charts (the whole run) or the last 200u"),
    ("r", "restart all three models at t = 0"),
    (
        "[ / ]",
        "off: I₃/I₁ is for symmetric tops; I is set in the scene",
    ),
    (
        "m",
        "method of (3.3) and the reduced model: {cycle}, and back to auto (no closed forms; the physical column always shoots backward)",
    ),
];

/// What the help says instead for the full ALE.
const FULL_KEYS: [(&str, &str); 2] = [
    ("r", "restart both runs at t = 0"),
    (
        "m",
        "off: each column has its own method (backward shooting, forward DOP853)",
    ),
];

/// The panels of a column, and the marks in its title.
const PANELS: [(&str, &str); 7] = [
    (
        "Ω(t)",
        "Ω₁, Ω₂, Ω₃ (body frame) and Ω⊥ = √(Ω₁² + Ω₂²) against t; each curve has its colour, and its own mark when NO_COLOR is set (the title shows which)",
    ),
    (
        "hodograph",
        "the tip of Ω in the body frame seen from aside, Ω₃ up, in units of the column's scale; the dots below are its shadow on the Ω₁Ω₂ plane",
    ),
    (
        "top in space",
        "the symmetry axis e₃ with the body as a disc, L, and the trail of the axis tip: the precession cone. Lab z is along L₀ where the view picks the start; a scene with Euler angles of its own keeps its lab frame, and the title gives the angle of e₃ from lab z (e₃∠z)",
    ),
    (
        "ran away",
        "the forward run of (3.4) left the physical solution, as it must; why is in its last row",
    ),
    (
        "stopped",
        "the model failed numerically; its last row says why and what to try",
    ),
    (
        "= reduced here",
        "τ_f|Ω₀| is so small that the physical solution is the reduced model to the screen's resolution: the reduced model stands in",
    ),
    (
        "model k of n",
        "one model at a time on a narrow screen; Tab shows the next",
    ),
];

/// The rows of numbers under each column.
const ROWS: [(&str, &str); 12] = [
    ("t", "the model's time"),
    ("E", "the kinetic energy ½ Ω·IΩ"),
    ("|L|", "the length of the angular momentum L = IΩ"),
    (
        "tilt",
        "the angle between the symmetry axis e₃ and L (the paper's θ where lab z is along L)",
    ),
    (
        "φ̇ ψ̇",
        "precession and spin rates (4.8); on the pole (θ = 0) only their sum is defined: — (pole)",
    ),
    (
        "method",
        "what this column runs; the reduced top's closed form still integrates its orientation, hence its steps",
    ),
    ("step", "the last accepted step; none for a closed form"),
    (
        "evals",
        "right-hand-side evaluations so far: the work the method has done",
    ),
    (
        "error",
        "|Ω − Ω_closed form| at the same t, from (4.7) and (4.15)–(4.16): how far the integrated Ω is from the exact one; 0 when the closed form itself is shown, — where a model has none",
    ),
    (
        "since t = 0",
        "a model without a closed form: E/E₀, |L|/|L₀| and the angle L has turned from L₀",
    ),
    ("Ω", "Ω now, and Ω⊥ (or, once stopped, why)"),
    (
        "header",
        "t, running / paused / running at the rate reached when the models fall behind the warp; the warp; Δt; the units; the parameters (the Ω₀ component selected is reversed)",
    ),
];

fn title(top: &Top) -> Vec<Line<'static>> {
    let (head, body): (&str, [&str; 3]) = match top {
        Top::General(_) => (
            "Duviryak's polarized top, any shape: the general top",
            [
                "The truncated ALE (3.3): loss law (2.1) for three different moments and a",
                "dipole anywhere in the body. Nothing is closed: Ω and the orientation are",
                "integrated together. Times are in u, the unit where κ = 2/(3c³) = 1.",
            ],
        ),
        Top::Full(_) => (
            "The full ALE (3.4): the physical solution and the runaway",
            [
                "Left: (3.4) solved backward from its slow manifold, where the runaway",
                "decays; it stays close to the reduced model. Right: the same equation",
                "integrated forward from the same start: it leaves at a rate ≈ 1/τ.",
            ],
        ),
        Top::Symmetric(_) => (
            "Duviryak's polarized spinning top, two ways",
            [
                "Left: truncated (4.2)–(4.4), loss law (2.1) without the Schott term.",
                "Right: reduced (4.12)–(4.14), Abraham–Lorentz torque (2.2) with it.",
                "Both start from the same I₃/I₁ and Ω₀; lab z is along L₀ unless a scene sets the start.",
            ],
        ),
    };
    let mut lines = vec![Line::from(Span::styled(head, theme::title()))];
    lines.extend(body.iter().map(|l| Line::from(*l)));
    lines
}

fn table(heading: &str, rows: &[(&str, &str)], key_width: usize) -> Vec<Line<'static>> {
    let mut lines = vec![
        Line::from(""),
        Line::from(Span::styled(heading.to_string(), theme::title())),
    ];
    for (key, what) in rows {
        let pad = key_width.saturating_sub(Span::raw(*key).width());
        lines.push(Line::from(vec![
            Span::styled(format!("{key}{}", " ".repeat(pad + 1)), theme::key()),
            Span::raw(what.to_string()),
        ]));
    }
    lines
}

/// The help for `top`: what it shows, the keys, the panels, the rows.
pub fn lines(top: &Top) -> Vec<Line<'static>> {
    let instead: &[(&str, &str)] = match top {
        Top::General(_) => &GENERAL_KEYS,
        Top::Full(_) => &FULL_KEYS,
        Top::Symmetric(_) => &[],
    };
    let keys: Vec<(&str, &str)> = KEYS
        .iter()
        .map(|(key, what)| {
            let what = instead
                .iter()
                .find(|(k, _)| k == key)
                .map_or(*what, |(_, w)| *w);
            (*key, what)
        })
        .collect();
    // `m` names the methods of its cycle, from the cycle itself.
    let cycle: Vec<String> = super::layout::method_cycle(top)
        .into_iter()
        .map(|m| super::layout::method_title(m, top))
        .collect();
    let m_says = keys
        .iter()
        .find(|(k, _)| *k == "m")
        .map(|(_, what)| what.replace("{cycle}", &cycle.join(", ")));
    let keys: Vec<(&str, &str)> = keys
        .into_iter()
        .map(|(k, what)| match (&m_says, k) {
            (Some(m), "m") => (k, m.as_str()),
            _ => (k, what),
        })
        .collect();
    let mut lines = title(top);
    lines.extend(table("Keys", &keys, 9));
    lines.extend(table("Each column: the panels", &PANELS, 15));
    lines.extend(table("Each column: the numbers", &ROWS, 12));
    lines
}
