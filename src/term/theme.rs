//! Every colour and style of both views, in one place.
//!
//! Plain 16-colour ANSI names, so the views read the same in any terminal
//! theme and under tmux. With `NO_COLOR` set the terminal draws no colour
//! (crossterm honours it); what colour alone told apart gets a mark of its
//! own then ([`no_color`]).

use ratatui::style::{Color, Modifier, Style};

/// The colours of Ω₁, Ω₂, Ω₃ and Ω⊥, in every chart and legend.
pub const OMEGA: [Color; 4] = [
    Color::LightRed,
    Color::LightGreen,
    Color::LightBlue,
    Color::Yellow,
];

/// The symmetry axis O·e₃ in the top-in-space panel.
pub const AXIS: Color = Color::Cyan;

/// The angular momentum direction.
pub const MOMENTUM: Color = Color::Magenta;

/// Trails (the hodograph and the precession cone).
pub const TRAIL: Color = Color::Gray;

/// Reference lines: coordinate axes, projections.
pub const GUIDE: Color = Color::DarkGray;

/// True when the user asked for no colour (`NO_COLOR` set and not empty,
/// as no-color.org defines it).
pub fn no_color() -> bool {
    std::env::var_os("NO_COLOR").is_some_and(|v| !v.is_empty())
}

/// Take every colour out of `buffer`, keeping the emphasis (reversed,
/// bold, underlined): what `NO_COLOR` asks for, and no more.
pub fn strip_colours(buffer: &mut ratatui::buffer::Buffer) {
    for cell in &mut buffer.content {
        cell.fg = Color::Reset;
        cell.bg = Color::Reset;
    }
}

/// Titles of panels.
pub fn title() -> Style {
    Style::new().add_modifier(Modifier::BOLD)
}

/// Borders and axis lines.
pub fn frame() -> Style {
    Style::new().fg(Color::DarkGray)
}

/// Labels of numbers and axes.
pub fn label() -> Style {
    Style::new().fg(Color::Gray)
}

/// Values of numbers.
pub fn value() -> Style {
    Style::new().add_modifier(Modifier::BOLD)
}

/// A key name in the footer and the help.
pub fn key() -> Style {
    Style::new().fg(Color::Yellow).add_modifier(Modifier::BOLD)
}

/// The selected Ω₀ component, and the edit field.
pub fn selected() -> Style {
    Style::new().add_modifier(Modifier::REVERSED)
}

/// A refusal or a failure.
pub fn error() -> Style {
    Style::new()
        .fg(Color::LightRed)
        .add_modifier(Modifier::BOLD)
}

/// A confirmation.
pub fn info() -> Style {
    Style::new().fg(Color::Green)
}

/// "running" / "paused".
pub fn status(paused: bool) -> Style {
    if paused {
        Style::new().fg(Color::Black).bg(Color::Yellow)
    } else {
        Style::new().fg(Color::Black).bg(Color::Green)
    }
}
