//! Where the screen's parts are, for a terminal of one size: the apply
//! step (rendering width, page height) and the drawing use the same.
//!
//! From 80 columns the chapter's scene stands beside the text, as in a
//! book with its figure in the margin: at 120 and wider the two share the
//! width; between 80 and 120 the text keeps at least [`TEXT_MIN`] columns
//! and the scene takes the rest, up to [`SCENE_MAX`] (its models then take
//! turns where a column does not fit). `w` hides the scene, `s` shows it
//! full screen.

use ratatui::layout::{Constraint, Layout, Rect};

/// Where the screen's parts are.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Panes {
    /// The header line.
    pub header: Rect,
    /// The text's frame, if the text is shown.
    pub text: Option<Rect>,
    /// The scene, if shown.
    pub scene: Option<Rect>,
    /// The status line.
    pub status: Rect,
    /// The keys.
    pub footer: Rect,
}

/// The smallest terminal `spintop learn` draws in.
pub const MIN_SIZE: (u16, u16) = (40, 10);

/// From this width the scene stands beside the text.
pub const SIDE_BY_SIDE: u16 = 80;

/// From this width text and scene share the width equally.
pub const HALVES: u16 = 120;

/// The narrowest the text gets beside a scene.
pub const TEXT_MIN: u16 = 46;

/// The widest a scene gets on a screen narrower than [`HALVES`].
pub const SCENE_MAX: u16 = 42;

/// The panes of a `size` terminal with the scene full screen (`scene_full`)
/// or not, and whether a scene stands beside the text (the chapter has one
/// and it is not hidden).
pub fn panes(size: (u16, u16), scene_full: bool, beside: bool) -> Panes {
    let area = Rect::new(0, 0, size.0, size.1);
    let [header, body, status, footer] = Layout::vertical([
        Constraint::Length(1),
        Constraint::Fill(1),
        Constraint::Length(1),
        Constraint::Length(1),
    ])
    .areas(area);
    let (text, scene) = if scene_full {
        (None, Some(body))
    } else if beside && body.width >= SIDE_BY_SIDE {
        let scene_width = if body.width >= HALVES {
            body.width / 2
        } else {
            SCENE_MAX.min(body.width - TEXT_MIN)
        };
        let [left, right] =
            Layout::horizontal([Constraint::Fill(1), Constraint::Length(scene_width)]).areas(body);
        (Some(left), Some(right))
    } else {
        (Some(body), None)
    };
    Panes {
        header,
        text,
        scene,
        status,
        footer,
    }
}

/// The text's lines area inside its frame (the right column is the
/// position mark).
pub fn text_inner(frame: Rect) -> Rect {
    let inner = Rect {
        x: frame.x + 1,
        y: frame.y + 1,
        width: frame.width.saturating_sub(2),
        height: frame.height.saturating_sub(2),
    };
    Rect {
        width: inner.width.saturating_sub(1).max(20),
        ..inner
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scene_stands_beside_the_text_from_80_columns() {
        let p = panes((80, 24), false, true);
        let (text, scene) = (p.text.unwrap(), p.scene.unwrap());
        assert!(
            text.width >= TEXT_MIN && scene.width >= 30,
            "{text:?} {scene:?}"
        );
        assert_eq!(text.width + scene.width, 80);
        let p = panes((160, 48), false, true);
        assert_eq!(p.text.unwrap().width, 80);
        assert!(panes((79, 24), false, true).scene.is_none());
        assert!(panes((100, 30), false, false).scene.is_none());
    }
}
