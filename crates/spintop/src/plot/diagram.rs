//! The book's diagrams, drawn as SVG from spintop's own vectors: the frames of
//! the top and the dipole, the Euler angles, the precession cone, the free
//! top's body and space cones, and the charge as a small shell.
//!
//! Output formatting only: every vector comes from the physics modules (an
//! orientation from [`EulerAngles`], the free motion from the truncated
//! closed form with τ = 0, the tilt of (4.11) from [`precession_tilt`]), and
//! this module only projects and draws them. Nothing is placed by hand but the
//! labels' offsets.
//!
//! The projection is orthographic and **right-handed**: the viewer looks down
//! on the lab's xy plane from the azimuth `azimuth` and the elevation
//! `elevation` above it, so lab z points up the page and x̂ × ŷ = ẑ on the
//! page as in the world. Each drawn frame is a `<g class="frame">` whose
//! three axes carry, besides their two screen coordinates, the depth of their
//! tip toward the viewer (`data-depth`, in the same pixels): a test
//! (`tests/project/book.rs`) rebuilds the three vectors from the SVG alone and
//! checks that they are orthogonal and right-handed, that every cone's edges
//! end on its rim, and that no two labels overlap.
//!
//! | diagram | what it shows | vectors from |
//! |---|---|---|
//! | `top-axes-dipole` | lab axes, body axes e₁, e₂, e₃, the dipole d along e₃ | `EulerAngles::to_rotation` |
//! | `euler-angles` | φ about z, θ about the line of nodes N, ψ about e₃ | `EulerAngles`, `rot_axis` |
//! | `precession-cone` | L, e₃ at the tilt θ, Ω between them, the cone and the sense of the precession | `truncated_orientation` (τ = 0), `precession_tilt` |
//! | `free-top-cones` | the body cone about e₃ rolling on the space cone about L, touching along Ω | the same free motion |
//! | `shell-model` | the charge as a shell of radius r₀, the delay δ = r₀/c, (A.1) | – (a plane sketch) |

use crate::math::{Mat3, Real, Vec3, rot_axis, rot_z};
use crate::physics::euler_angles::{EulerAngles, frame_with_z_along};
use crate::physics::symmetric_top::{
    SymmetricTop, precession_tilt, truncated_closed_form, truncated_orientation,
};
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use std::fmt::Write as _;

/// The lab frame's colour.
const GREY: &str = "#888888";
/// Body axes and the symmetry axis.
const BLUE: &str = "#1f5fbf";
/// L and the dipole.
const RED: &str = "#c0392b";
/// Angles and the angular velocity.
const GREEN: &str = "#1e8449";
/// The third Euler angle.
const PURPLE: &str = "#8e44ad";

/// One diagram of the book: its file name (without `.svg`) and the document.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagram {
    /// The name, also the file name in `book/src/figures/` without `.svg`.
    pub name: &'static str,
    /// One line on what it shows (the SVG's title).
    pub title: &'static str,
    /// The SVG document.
    pub svg: String,
}

/// The names of every diagram, in the order of [`all`].
pub const NAMES: [&str; 5] = [
    "top-axes-dipole",
    "euler-angles",
    "precession-cone",
    "free-top-cones",
    "shell-model",
];

/// Every diagram of the book.
pub fn all() -> Vec<Diagram> {
    vec![
        top_axes_dipole(),
        euler_angles(),
        precession_cone(),
        free_top_cones(),
        shell_model(),
    ]
}

/// The diagram called `name`, if there is one.
pub fn by_name(name: &str) -> Option<Diagram> {
    all().into_iter().find(|d| d.name == name)
}

/// An orthographic view from above, right-handed on the page.
#[derive(Clone, Copy, Debug)]
struct View {
    /// Screen right, screen up and toward the viewer, in lab coordinates.
    right: Vec3,
    up: Vec3,
    toward: Vec3,
    /// Pixels per unit length, and the page position of the lab origin.
    scale: Real,
    origin: (Real, Real),
}

impl View {
    /// The viewer sits at `azimuth` from lab x (about z) and `elevation` above
    /// the xy plane (0 < elevation < π/2: seen from above).
    fn new(azimuth: Real, elevation: Real, scale: Real, origin: (Real, Real)) -> Self {
        let (sa, ca) = azimuth.sin_cos();
        let (se, ce) = elevation.sin_cos();
        let toward = Vec3::new(ce * ca, ce * sa, se);
        let right = Vec3::new(-sa, ca, 0.0);
        // (right, up, toward) is right-handed: right × up = toward.
        let up = toward.cross(&right);
        Self {
            right,
            up,
            toward,
            scale,
            origin,
        }
    }

    /// Page coordinates (x right, y down, as SVG has them) of a lab point.
    fn page(&self, p: &Vec3) -> (Real, Real) {
        (
            self.origin.0 + self.scale * p.dot(&self.right),
            self.origin.1 - self.scale * p.dot(&self.up),
        )
    }

    /// The depth of a lab point toward the viewer, in pixels.
    fn depth(&self, p: &Vec3) -> Real {
        self.scale * p.dot(&self.toward)
    }
}

/// A label placed on the page; kept to let the drawing avoid overlaps.
struct Label {
    x: Real,
    y: Real,
    text: String,
    color: &'static str,
    size: Real,
    anchor: &'static str,
    italic: bool,
}

/// An SVG document under construction.
struct Svg {
    width: u32,
    height: u32,
    body: String,
    labels: Vec<Label>,
}

impl Svg {
    fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            body: String::new(),
            labels: Vec::new(),
        }
    }

    fn line(&mut self, a: (Real, Real), b: (Real, Real), color: &str, width: Real, extra: &str) {
        let _ = writeln!(
            self.body,
            r#"<line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="{color}" stroke-width="{width}"{extra}/>"#,
            a.0, a.1, b.0, b.1
        );
    }

    /// A polyline through page points; `extra` adds attributes (class, dashes, a marker).
    fn polyline(&mut self, points: &[(Real, Real)], color: &str, width: Real, extra: &str) {
        let mut d = String::new();
        for (i, p) in points.iter().enumerate() {
            let _ = write!(
                d,
                "{}{:.1},{:.1} ",
                if i == 0 { "M" } else { "L" },
                p.0,
                p.1
            );
        }
        let _ = writeln!(
            self.body,
            r#"<path d="{}" fill="none" stroke="{color}" stroke-width="{width}"{extra}/>"#,
            d.trim_end()
        );
    }

    #[allow(clippy::too_many_arguments)]
    fn label(
        &mut self,
        at: (Real, Real),
        text: &str,
        color: &'static str,
        size: Real,
        anchor: &'static str,
        italic: bool,
    ) {
        self.labels.push(Label {
            x: at.0,
            y: at.1,
            text: text.to_string(),
            color,
            size,
            anchor,
            italic,
        });
    }

    /// A label beside the tip of an arrow from `from` to `to`, pushed out
    /// along the arrow by `gap` pixels.
    fn label_at_tip(
        &mut self,
        from: (Real, Real),
        to: (Real, Real),
        text: &str,
        color: &'static str,
        gap: Real,
    ) {
        let (dx, dy) = (to.0 - from.0, to.1 - from.1);
        let n = dx.hypot(dy).max(1e-9);
        let (ux, uy) = (dx / n, dy / n);
        let size = 17.0;
        // Centre the text on the point beyond the tip: half its width to the
        // side the arrow points to, the baseline a third of its height down.
        let (x, y) = (to.0 + gap * ux, to.1 + gap * uy + 0.35 * size);
        self.label((x, y), text, color, size, "middle", true);
    }

    /// The line of small print under a drawing.
    fn caption(&mut self, y: Real, text: &str) {
        self.label((20.0, y), text, "black", 12.0, "start", false);
    }

    /// The diagram called `name`, with `title` as the SVG's title.
    fn diagram(self, name: &'static str, title: &'static str) -> Diagram {
        Diagram {
            name,
            title,
            svg: self.finish(title),
        }
    }

    fn finish(mut self, title: &str) -> String {
        let mut out = String::new();
        let _ = writeln!(
            out,
            r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {w} {h}" width="{w}" height="{h}" font-family="serif" font-size="16">"#,
            w = self.width,
            h = self.height
        );
        let _ = writeln!(out, "<title>{}</title>", escape(title));
        out.push_str(
            r#"<defs>
<marker id="a" viewBox="0 0 10 10" refX="9" refY="5" markerUnits="userSpaceOnUse" markerWidth="11" markerHeight="11" orient="auto-start-reverse"><path d="M0,0 L10,5 L0,10 z" fill="context-stroke"/></marker>
</defs>
"#,
        );
        let _ = writeln!(
            out,
            r#"<rect width="{}" height="{}" fill="white"/>"#,
            self.width, self.height
        );
        out.push_str(&self.body);
        for l in self.labels.drain(..) {
            let _ = writeln!(
                out,
                r#"<text class="label" x="{:.1}" y="{:.1}" fill="{}" font-size="{}" text-anchor="{}"{}>{}</text>"#,
                l.x,
                l.y,
                l.color,
                l.size,
                l.anchor,
                if l.italic {
                    r#" font-style="italic""#
                } else {
                    ""
                },
                escape(&l.text)
            );
        }
        out.push_str("</svg>\n");
        out
    }
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// Draw a frame: three arrows from `at` along the columns of `axes` (lab
/// vectors), each tagged with its name and the depth of its tip toward the
/// viewer, so that a reader of the SVG can rebuild the frame in 3D.
#[allow(clippy::too_many_arguments)]
fn frame(
    svg: &mut Svg,
    view: &View,
    id: &str,
    at: &Vec3,
    axes: [(&str, Vec3, &'static str); 3],
    color: &'static str,
    width: Real,
    labels: bool,
) {
    let o = view.page(at);
    let _ = writeln!(svg.body, r#"<g class="frame" data-frame="{id}">"#);
    for (name, v, label) in axes {
        let tip = at + v;
        let t = view.page(&tip);
        let depth = view.depth(&tip) - view.depth(at);
        svg.line(
            o,
            t,
            color,
            width,
            &format!(
                r#" class="axis" data-axis="{name}" data-depth="{depth:.2}" marker-end="url(#a)""#
            ),
        );
        if labels {
            svg.label_at_tip(o, t, label, color, 14.0);
        }
    }
    svg.body.push_str("</g>\n");
}

/// An arrow between two lab points.
fn arrow(svg: &mut Svg, view: &View, from: &Vec3, to: &Vec3, color: &str, width: Real) {
    svg.line(
        view.page(from),
        view.page(to),
        color,
        width,
        r#" marker-end="url(#a)""#,
    );
}

/// An arc of radius `radius` about the unit `axis` through `centre`, from
/// the direction `start` (perpendicular to the axis) turning by `angle` in
/// the right-handed sense about the axis, with an arrowhead at its end.
/// Returns the point for its name, beyond the middle of the arc.
#[allow(clippy::too_many_arguments)]
fn arc(
    svg: &mut Svg,
    view: &View,
    centre: &Vec3,
    axis: &Vec3,
    start: &Vec3,
    radius: Real,
    angle: Real,
    color: &str,
    about: &str,
) -> Vec3 {
    let n = 48;
    let points: Vec<(Real, Real)> = (0..=n)
        .map(|i| {
            let r = rot_axis(axis, angle * i as Real / n as Real);
            view.page(&(centre + radius * (r * start.normalize())))
        })
        .collect();
    let c = view.page(centre);
    svg.polyline(
        &points,
        color,
        1.6,
        &format!(
            r#" class="arc" data-about="{about}" data-cx="{:.1}" data-cy="{:.1}" marker-end="url(#a)""#,
            c.0, c.1
        ),
    );
    // Where the arc's name goes: beyond its middle, outward.
    centre + 1.4 * radius * (rot_axis(axis, 0.5 * angle) * start.normalize())
}

/// A circle of the cone with apex `apex` about the unit `axis`, at distance
/// `along` from the apex, of radius `radius`, drawn with its hidden half
/// dashed, and the cone's two edges from the apex to the points where the
/// rim's outline turns (where the edge is tangent to the projected rim).
#[allow(clippy::too_many_arguments)]
fn cone(
    svg: &mut Svg,
    view: &View,
    id: &str,
    apex: &Vec3,
    axis: &Vec3,
    along: Real,
    radius: Real,
    color: &str,
) {
    let n = axis.normalize();
    let u = n
        .cross(&view.toward)
        .try_normalize(1e-12)
        .unwrap_or_else(|| {
            // Seen along the axis: any perpendicular will do.
            n.cross(&Vec3::x()).normalize()
        });
    let w = n.cross(&u);
    let centre = apex + along * n;
    let rim = |s: Real| centre + radius * (s.cos() * u + s.sin() * w);
    let a = view.page(apex);
    // The edge from the apex touches the projected rim where the rim's
    // tangent passes through the apex: a sign change of this cross product.
    let turn = |s: Real| {
        let p = view.page(&rim(s));
        let h = 1e-6;
        let q = view.page(&rim(s + h));
        (p.0 - a.0) * (q.1 - p.1) - (p.1 - a.1) * (q.0 - p.0)
    };
    let samples = 720;
    let mut tangents = Vec::new();
    for i in 0..samples {
        let (s0, s1) = (
            TAU * i as Real / samples as Real,
            TAU * (i + 1) as Real / samples as Real,
        );
        if turn(s0).signum() != turn(s1).signum() {
            let (mut lo, mut hi) = (s0, s1);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if turn(lo).signum() == turn(mid).signum() {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            tangents.push(0.5 * (lo + hi));
        }
    }
    // The rim, split at the two tangent points: the half nearer the viewer
    // solid, the other dashed.
    let arc_points = |from: Real, to: Real| -> Vec<(Real, Real)> {
        let m = 96;
        (0..=m)
            .map(|i| view.page(&rim(from + (to - from) * i as Real / m as Real)))
            .collect()
    };
    if let [s1, s2] = tangents[..] {
        let (first, second) = ((s1, s2), (s2, s1 + TAU));
        let mean_depth = |(from, to): (Real, Real)| view.depth(&rim(0.5 * (from + to)));
        let (front, back) = if mean_depth(first) > mean_depth(second) {
            (first, second)
        } else {
            (second, first)
        };
        svg.polyline(
            &arc_points(back.0, back.1),
            color,
            1.2,
            &format!(r#" class="rim" data-cone="{id}" stroke-dasharray="5 4""#),
        );
        svg.polyline(
            &arc_points(front.0, front.1),
            color,
            1.6,
            &format!(r#" class="rim" data-cone="{id}""#),
        );
        for s in [s1, s2] {
            svg.line(
                a,
                view.page(&rim(s)),
                color,
                1.2,
                &format!(r#" class="cone-edge" data-cone="{id}""#),
            );
        }
    } else {
        svg.polyline(
            &arc_points(0.0, TAU),
            color,
            1.6,
            &format!(r#" class="rim" data-cone="{id}""#),
        );
    }
}

/// The lab frame's three axes, drawn grey at `at` with length `len`.
fn lab_frame(svg: &mut Svg, view: &View, at: &Vec3, len: Real, labels: bool) {
    frame(
        svg,
        view,
        "lab",
        at,
        [
            ("x", len * Vec3::x(), "x"),
            ("y", len * Vec3::y(), "y"),
            ("z", len * Vec3::z(), "z"),
        ],
        GREY,
        1.4,
        labels,
    );
}

/// The standard view of the book's diagrams: from the front right, above.
fn book_view(scale: Real, origin: (Real, Real)) -> View {
    View::new(0.75, 0.42, scale, origin)
}

/// A symmetric top with body axes e₁, e₂, e₃ and its dipole d along e₃.
fn top_axes_dipole() -> Diagram {
    let title = "A symmetric top with body axes e1, e2, e3 and its dipole d along e3, in the lab frame x, y, z";
    let mut svg = Svg::new(520, 330);
    let view = book_view(150.0, (250.0, 200.0));
    lab_frame(&mut svg, &view, &Vec3::zeros(), 1.2, true);
    let o = EulerAngles::new(1.05, 0.5, 1.0).to_rotation();
    let (e1, e2, e3) = (
        o.column(0).into_owned(),
        o.column(1).into_owned(),
        o.column(2).into_owned(),
    );
    // The top: a disc about e3 at mid-height, seen through.
    let disc: Vec<(Real, Real)> = (0..=96)
        .map(|i| {
            let s = TAU * i as Real / 96.0;
            view.page(&(0.45 * e3 + 0.42 * (s.cos() * e1 + s.sin() * e2)))
        })
        .collect();
    svg.polyline(&disc, "#555555", 1.0, "");
    frame(
        &mut svg,
        &view,
        "body",
        &Vec3::zeros(),
        [
            ("e1", 0.9 * e1, "e₁"),
            ("e2", 0.9 * e2, "e₂"),
            ("e3", 1.05 * e3, "e₃"),
        ],
        BLUE,
        2.0,
        true,
    );
    let d_from = view.page(&(0.15 * e3));
    let d_to = view.page(&(0.62 * e3));
    svg.line(d_from, d_to, RED, 3.5, r#" marker-end="url(#a)""#);
    let beside = view.page(&(0.4 * e3));
    svg.label(
        (beside.0 - 12.0, beside.1 + 4.0),
        "d",
        RED,
        18.0,
        "end",
        true,
    );
    svg.caption(318.0, "lab frame x, y, z (grey); body axes e₁, e₂, e₃ (blue); the dipole d = Σ q ρ along e₃ (red)");
    svg.diagram("top-axes-dipole", title)
}

/// The z-x-z Euler angles: φ about lab z, θ about the line of nodes N, ψ about e₃.
fn euler_angles() -> Diagram {
    let title = "The z-x-z Euler angles phi, theta, psi of (3.5): O = Rz(phi) Rx(theta) Rz(psi)";
    let mut svg = Svg::new(520, 390);
    let view = book_view(150.0, (250.0, 240.0));
    lab_frame(&mut svg, &view, &Vec3::zeros(), 1.25, true);
    let angles = EulerAngles::new(0.95, 0.6, 1.0);
    let o = angles.to_rotation();
    let node = rot_z(angles.phi) * Vec3::x();
    let (e1, e2, e3) = (
        o.column(0).into_owned(),
        o.column(1).into_owned(),
        o.column(2).into_owned(),
    );
    frame(
        &mut svg,
        &view,
        "body",
        &Vec3::zeros(),
        [("e1", e1, "e₁"), ("e2", e2, "e₂"), ("e3", 1.05 * e3, "e₃")],
        BLUE,
        2.0,
        true,
    );
    // The line of nodes, where the body's e1e2 plane cuts the lab's xy plane.
    let n_tip = 1.15 * node;
    svg.line(
        view.page(&Vec3::zeros()),
        view.page(&n_tip),
        "black",
        1.2,
        r#" stroke-dasharray="6 4""#,
    );
    let n_page = view.page(&n_tip);
    svg.label(
        (n_page.0 + 6.0, n_page.1 + 18.0),
        "N",
        "black",
        16.0,
        "start",
        true,
    );
    // φ: from x to N about z; θ: from z to e3 about N; ψ: from N to e1 about e3.
    let names = [
        (
            arc(
                &mut svg,
                &view,
                &Vec3::zeros(),
                &Vec3::z(),
                &Vec3::x(),
                0.5,
                angles.phi,
                GREEN,
                "z",
            ),
            "φ",
            GREEN,
        ),
        (
            arc(
                &mut svg,
                &view,
                &Vec3::zeros(),
                &node,
                &Vec3::z(),
                0.62,
                angles.theta,
                RED,
                "N",
            ),
            "θ",
            RED,
        ),
        (
            arc(
                &mut svg,
                &view,
                &Vec3::zeros(),
                &e3,
                &node,
                0.55,
                angles.psi,
                PURPLE,
                "e3",
            ),
            "ψ",
            PURPLE,
        ),
    ];
    for (at, text, color) in names {
        let p = view.page(&at);
        svg.label((p.0, p.1 + 6.0), text, color, 18.0, "middle", true);
    }
    svg.caption(
        378.0,
        "O = R_z(φ) R_x(θ) R_z(ψ): turn by φ about z, by θ about the node line N, by ψ about e₃",
    );
    svg.diagram("euler-angles", title)
}

/// The paper's top (Figures 1–2's I₃/I₁ and Ω₀) as the free motion sees it,
/// in the frame of (4.11), lab z along L: L, the orientation at time `t`, and
/// Ω there, all in the lab.
struct FreeTop {
    l: Vec3,
    e3: Vec3,
    omega: Vec3,
    tilt: Real,
}

fn free_top(t: Real) -> FreeTop {
    let free = SymmetricTop::new(0.4, 0.0).expect("2/5 is a valid I3/I1");
    let omega0 = Vec3::new(0.0, 0.1, 0.2);
    let l_body = free.inertia().component_mul(&omega0);
    let o0: Mat3 = frame_with_z_along(&l_body).to_rotation();
    let o = truncated_orientation(&free, &omega0, &o0, t);
    FreeTop {
        l: o0 * l_body,
        e3: o * Vec3::z(),
        omega: o * truncated_closed_form(&free, &omega0, t),
        tilt: precession_tilt(&free, &omega0),
    }
}

/// The time at which the free top's axis points to `azimuth` (about lab z).
fn time_at_azimuth(azimuth: Real) -> Real {
    let start = free_top(0.0).e3;
    let rate = free_top(0.0).l.norm(); // |L|/I1, I1 = 1
    let phase0 = start.y.atan2(start.x);
    (azimuth - phase0).rem_euclid(TAU) / rate
}

/// A small lab frame off to the lower left of a drawing, where L (along z)
/// does not hide its z axis.
fn corner_frame(svg: &mut Svg, view: &View, right: Real, up: Real) {
    let at = right * view.right + up * view.up;
    lab_frame(svg, view, &at, 0.3, true);
}

/// L, the symmetry axis at the tilt θ on its cone about L, Ω in their plane.
fn precession_cone() -> Diagram {
    let title = "The angular momentum L, the symmetry axis e3 at the tilt theta, the angular velocity Omega in their plane, and the precession cone";
    let mut svg = Svg::new(520, 375);
    // A little higher than the other diagrams, so the rim opens up.
    let view = View::new(0.75, 0.55, 210.0, (290.0, 300.0));
    // The axis to the back left, so that its turn comes round to the front.
    let top = free_top(time_at_azimuth(0.75 - 1.9));
    let (l_hat, e3) = (top.l.normalize(), top.e3);
    corner_frame(&mut svg, &view, 0.8, -0.05);
    cone(
        &mut svg,
        &view,
        "precession",
        &Vec3::zeros(),
        &l_hat,
        top.tilt.cos(),
        top.tilt.sin(),
        BLUE,
    );
    let o = view.page(&Vec3::zeros());
    // L (red), the axis (blue), Ω (green) at its true angle in their plane.
    for (v, text, color, width) in [
        (1.25 * l_hat, "L", RED, 3.0),
        (e3, "e₃", BLUE, 2.5),
        (0.8 * top.omega.normalize(), "Ω", GREEN, 2.2),
    ] {
        arrow(&mut svg, &view, &Vec3::zeros(), &v, color, width);
        svg.label_at_tip(o, view.page(&v), text, color, 12.0);
    }
    // θ between L and the axis, in its own colour: Ω's green would read as
    // the angle to Ω, which runs close to the arc's middle.
    let across = l_hat.cross(&e3).normalize();
    let (radius, angle) = (0.3, top.tilt);
    arc(
        &mut svg,
        &view,
        &Vec3::zeros(),
        &across,
        &l_hat,
        radius,
        angle,
        PURPLE,
        "L×e3",
    );
    // Its name between Ω and e3 (Ω lies near the arc's middle, at the angle
    // atan(Ω⊥/Ω₃) from e3), just outside the arc.
    let at = 1.4 * radius * (rot_axis(&across, 0.74 * angle) * l_hat);
    let p = view.page(&at);
    svg.label((p.0, p.1 + 6.0), "θ", PURPLE, 18.0, "middle", true);
    // The precession: e3 turns about L, in the right-handed sense.
    let rim_centre = top.tilt.cos() * l_hat;
    let turn = 1.0;
    arc(
        &mut svg,
        &view,
        &rim_centre,
        &l_hat,
        &(e3 - rim_centre),
        1.12 * top.tilt.sin(),
        turn,
        RED,
        "z",
    );
    let end = rim_centre
        + 1.12 * top.tilt.sin() * (rot_axis(&l_hat, turn) * (e3 - rim_centre).normalize());
    let p = view.page(&end);
    // Below the arrowhead, clear of the rim.
    svg.label(
        (p.0 - 6.0, p.1 + 30.0),
        "φ̇ = |L|/I₁",
        RED,
        16.0,
        "middle",
        true,
    );
    svg.caption(
        363.0,
        "truncated top: θ = arctan(I₁Ω⊥₀/(I₃Ω₃₀)) for ever; reduced top: θ → 0 like e^(−t/σ)",
    );
    svg.diagram("precession-cone", title)
}

/// The free top: the body cone about e₃ rolls on the space cone about L,
/// and the two touch along Ω.
fn free_top_cones() -> Diagram {
    let title = "The free symmetric top: the body cone about e3 rolls on the space cone about L; they touch along Omega";
    let mut svg = Svg::new(520, 470);
    let view = book_view(230.0, (320.0, 320.0));
    // The plane of L, e3 and Ω faces the viewer.
    let top = free_top(time_at_azimuth(0.75 - FRAC_PI_2));
    let (l_hat, e3, w_hat) = (top.l.normalize(), top.e3, top.omega.normalize());
    corner_frame(&mut svg, &view, 0.5, -0.33);
    let space = l_hat.angle(&w_hat);
    let body = e3.angle(&w_hat);
    // Both cones reach out to the same length along their common edge Ω.
    cone(
        &mut svg,
        &view,
        "space",
        &Vec3::zeros(),
        &l_hat,
        space.cos(),
        space.sin(),
        RED,
    );
    cone(
        &mut svg,
        &view,
        "body",
        &Vec3::zeros(),
        &e3,
        body.cos(),
        body.sin(),
        BLUE,
    );
    let o = view.page(&Vec3::zeros());
    for (v, text, color, len) in [
        (l_hat, "L", RED, 1.3),
        (e3, "e₃", BLUE, 1.3),
        (w_hat, "Ω", GREEN, 1.2),
    ] {
        let tip = len * v;
        arrow(&mut svg, &view, &Vec3::zeros(), &tip, color, 2.4);
        svg.label_at_tip(o, view.page(&tip), text, color, 12.0);
    }
    // Each cone's name beside the rim point farthest from Ω.
    let far_side = |axis: Vec3, angle: Real| {
        let side = (w_hat - axis * axis.dot(&w_hat)).normalize();
        view.page(&(axis * angle.cos() - side * angle.sin()))
    };
    let (s, b) = (far_side(l_hat, space), far_side(e3, body));
    svg.label(
        (s.0 + 12.0, s.1 + 5.0),
        "space cone",
        RED,
        14.0,
        "start",
        false,
    );
    svg.label(
        (b.0 - 12.0, b.1 + 5.0),
        "body cone",
        BLUE,
        14.0,
        "end",
        false,
    );
    svg.caption(
        458.0,
        "Ω = L/I₁ + Ω̃₃e₃: e₃ turns about L at |L|/I₁, and Ω turns about e₃ in the body at −Ω̃₃",
    );
    svg.diagram("free-top-cones", title)
}

/// The charge as a small shell (a plane sketch of the appendix's model).
fn shell_model() -> Diagram {
    let title = "The charge as a small shell of radius r0: the delay from the centre to the shell is delta = r0 / c";
    let mut svg = Svg::new(560, 350);
    let (cx, cy, r) = (196.0, 185.0, 110.0);
    let ring: Vec<(Real, Real)> = (0..=96)
        .map(|i| {
            let s = TAU * i as Real / 96.0;
            (cx + r * s.cos(), cy + r * s.sin())
        })
        .collect();
    svg.polyline(&ring, RED, 2.0, "");
    for i in 0..16 {
        let s = TAU * i as Real / 16.0;
        svg.label(
            (cx + r * s.cos(), cy + r * s.sin() + 5.0),
            "+",
            RED,
            14.0,
            "middle",
            false,
        );
    }
    // The radius, and the signal that crosses it in δ = r₀/c.
    svg.line((cx, cy), (cx + r, cy), "black", 1.2, "");
    svg.label(
        (cx + 0.5 * r, cy - 8.0),
        "r₀",
        "black",
        16.0,
        "middle",
        true,
    );
    // The signal from the centre to the shell takes δ = r₀/c.
    let (s, c) = (0.75 * PI).sin_cos();
    svg.line(
        (cx, cy),
        (cx + 0.97 * r * c, cy + 0.97 * r * s),
        GREEN,
        1.6,
        r#" stroke-dasharray="5 3" marker-end="url(#a)""#,
    );
    svg.label(
        (cx - 8.0, cy + 0.62 * r),
        "signal: δ = r₀/c",
        GREEN,
        14.0,
        "middle",
        true,
    );
    svg.label(
        (330.0, 45.0),
        "F = −k r (the spring)",
        "black",
        14.0,
        "start",
        true,
    );
    svg.label((340.0, 140.0), "m = m₀ + mₑₘ", "black", 16.0, "start", true);
    svg.label(
        (340.0, 170.0),
        "mₑₘ = mτ₀/δ: the field's mass,",
        "black",
        13.0,
        "start",
        false,
    );
    svg.label(
        (340.0, 188.0),
        "felt one delay late",
        "black",
        13.0,
        "start",
        false,
    );
    svg.label(
        (340.0, 218.0),
        "m₀ v̇(t) + mₑₘ v̇(t − δ) = F(t)",
        "black",
        14.0,
        "start",
        true,
    );
    svg.caption(335.0, "(A.1): the self-force of a rigid charged shell, to leading order in r₀, is a retarded mass term");
    svg.diagram("shell-model", title)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The view is right-handed: the page images of x̂ and ŷ turn
    /// counterclockwise (x̂ × ŷ = ẑ, with ẑ toward the viewer) and z is up.
    #[test]
    fn the_view_is_right_handed_and_from_above() {
        let v = book_view(100.0, (0.0, 0.0));
        let page_up = |p: Vec3| {
            let (x, y) = v.page(&p);
            (x, -y)
        };
        let (x, y, z) = (page_up(Vec3::x()), page_up(Vec3::y()), page_up(Vec3::z()));
        assert!(x.0 * y.1 - x.1 * y.0 > 0.0);
        assert!(z.1 > 0.0 && v.depth(&Vec3::z()) > 0.0);
        // Seen from the front right: x comes out to the left, y to the right.
        assert!(x.0 < 0.0 && y.0 > 0.0);
        assert!(v.right.cross(&v.up).dot(&v.toward) > 1.0 - 1e-15);
    }

    #[test]
    fn every_diagram_has_a_title_and_a_unique_name() {
        let all = all();
        assert_eq!(all.len(), NAMES.len());
        for (d, name) in all.iter().zip(NAMES) {
            assert_eq!(d.name, name);
            assert!(d.svg.starts_with("<svg") && d.svg.contains("<title>"));
            assert!(by_name(name).is_some());
        }
        assert!(by_name("nothing").is_none());
    }

    /// The precession cone's vectors are the free top's: Ω lies in the plane
    /// of L and e₃, at the angles of the book's text.
    #[test]
    fn the_free_top_of_the_diagrams_is_the_papers() {
        let top = free_top(time_at_azimuth(-0.2));
        assert!(top.l.normalize().dot(&Vec3::z()) > 1.0 - 1e-15);
        assert!((top.e3.angle(&top.l) - 0.8960554).abs() < 1e-6);
        assert!(top.omega.dot(&top.l.cross(&top.e3)).abs() < 1e-15);
        assert!((top.omega.angle(&top.e3) - 0.5f64.atan()).abs() < 1e-12);
        let azimuth = top.e3.y.atan2(top.e3.x);
        assert!((azimuth + 0.2).abs() < 1e-9);
    }
}
