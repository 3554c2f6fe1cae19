//! The paper's Figures 1 and 2, as spintop draws them.
//!
//! These tests pin down what the figures claim. Every plotted Ω lies on the
//! printed closed form, recomputed here from the paper's formulas (4.7) and
//! (4.15)–(4.16) with Ω₁₀ = 0, not through the crate. Figure 1's hodograph lies
//! on the cone Ω₃/Ω⊥ = Ω₃₀/Ω⊥₀, its axis keeps the tilt arctan(I₁Ω⊥₀/(I₃Ω₃₀))
//! from a fixed L, and its Euler angles advance as (4.11) on the clock ϑ.
//! Figure 2's hodograph lies in the plane Ω₃ = Ω₃₀ with Ω⊥ decreasing, its
//! orientation agrees with an independent DOP853 run of Ω and O together, and
//! its axis stands up along L∞ = lab z with the rates of (4.18). The SVG is
//! well formed, has one curve per plotted quantity and only finite coordinates
//! on the canvas. The command refuses a third figure and an unwritable path
//! with one line and exit code 2.

use spintop::figure::{FIGURE_OMEGA0, FIGURE_RATIO, Figure, FigureNumber};
use spintop::math::{Mat3, Vec3};
use spintop::physics::euler_angles::EulerAngles;
use spintop::physics::symmetric_top::SymmetricTop;
use spintop::plot::figure::{
    AXIS_COLOR, CURVE_COLOR, L_COLOR, PHI_DOT_COLOR, PROJECTION_COLOR, PSI_DOT_COLOR, SVG_SIZE,
    ascii, svg,
};
use spintop::sim::{InitialState, MethodChoice, MethodOptions, Model, Simulation};

use std::sync::OnceLock;

fn figure(number: FigureNumber) -> &'static Figure {
    static ONE: OnceLock<Figure> = OnceLock::new();
    static TWO: OnceLock<Figure> = OnceLock::new();
    let cell = match number {
        FigureNumber::One => &ONE,
        FigureNumber::Two => &TWO,
    };
    cell.get_or_init(|| Figure::new(number).expect("the paper's parameters run"))
}

const RATIO: f64 = 0.4;
const W20: f64 = 0.1;
const W30: f64 = 0.2;
const TAU: f64 = 1.0;

/// (4.7) as printed, Ω₁₀ = 0, I₁ = 1.
fn printed_4_7(t: f64) -> Vec3 {
    let r = (1.0 + 2.0 * TAU * W20 * W20 * t).sqrt();
    let w3t0 = (1.0 - RATIO) * W30;
    let phase = w3t0 * (r - 1.0) / (TAU * W20 * W20);
    Vec3::new(W20 / r * phase.sin(), W20 / r * phase.cos(), W30 / r)
}

/// (4.15)–(4.16) as printed, Ω₁₀ = 0, I₁ = 1.
fn printed_4_15(t: f64) -> Vec3 {
    let beta = 1.0 + (RATIO * W30).powi(2) / (W20 * W20);
    let sigma = 1.0 / ((RATIO * W30).powi(2) * TAU);
    let phi = ((beta - 1.0) / (beta * (2.0 * t / sigma).exp() - 1.0)).sqrt();
    let w3t = (1.0 - RATIO) * W30;
    Vec3::new(
        W20 * phi * (w3t * t).sin(),
        W20 * phi * (w3t * t).cos(),
        W30,
    )
}

fn angle(a: &Vec3, b: &Vec3) -> f64 {
    a.cross(b).norm().atan2(a.dot(b))
}

/// The difference of two angles, folded into (−π, π].
fn wrap(x: f64) -> f64 {
    let y = x.rem_euclid(std::f64::consts::TAU);
    if y > std::f64::consts::PI {
        y - std::f64::consts::TAU
    } else {
        y
    }
}

#[test]
fn figures_use_the_captions_parameters() {
    assert_eq!(FIGURE_RATIO, RATIO);
    assert_eq!(FIGURE_OMEGA0, [0.0, W20, W30]);
    for number in [FigureNumber::One, FigureNumber::Two] {
        let f = figure(number);
        assert_eq!(f.top(), SymmetricTop::new(0.4, 1.0).unwrap());
        assert_eq!(f.samples[0].omega, FIGURE_OMEGA0);
        assert_eq!(f.samples[0].t, 0.0);
        assert!(f.samples.windows(2).all(|w| w[1].t > w[0].t));
        assert!(f.samples.len() > 500, "smooth curves need many points");
    }
    assert!(matches!(
        figure(FigureNumber::One).model,
        Model::Truncated(_)
    ));
    assert!(matches!(figure(FigureNumber::Two).model, Model::Reduced(_)));
}

#[test]
fn eq_4_7_every_point_of_figure_1_lies_on_the_printed_closed_form() {
    for s in &figure(FigureNumber::One).samples {
        let expected = printed_4_7(s.t);
        let err = (s.omega_vec() - expected).norm() / expected.norm();
        assert!(err < 1e-12, "t = {}: relative error {err:e}", s.t);
    }
}

#[test]
fn eq_4_15_every_point_of_figure_2_lies_on_the_printed_closed_form() {
    for s in &figure(FigureNumber::Two).samples {
        let expected = printed_4_15(s.t);
        let err = (s.omega_vec() - expected).norm();
        // Ω₃ = 0.2 dominates the norm; compare Ω⊥ relatively as well.
        let perp = (s.omega_vec().xy() - expected.xy()).norm() / expected.xy().norm();
        assert!(
            err < 1e-14 && perp < 1e-11,
            "t = {}: {err:e}, {perp:e}",
            s.t
        );
    }
}

#[test]
fn sec4_1_figure_1_hodograph_lies_on_its_cone() {
    let f = figure(FigureNumber::One);
    let cone = W30 / W20;
    for s in &f.samples {
        assert!(
            (s.omega[2] / s.omega_perp - cone).abs() < 1e-12,
            "t = {}",
            s.t
        );
    }
    // And it spirals down it: |Ω| falls as 1/R, ten-fold by t = 5000.
    let last = f.samples.last().unwrap();
    assert!(
        (f.samples[0].omega_vec().norm() / last.omega_vec().norm() - 101f64.sqrt()).abs() < 1e-9
    );
}

#[test]
fn sec4_2_figure_2_hodograph_lies_in_the_plane_omega3_const_with_omega_perp_falling() {
    let f = figure(FigureNumber::Two);
    for s in &f.samples {
        assert_eq!(s.omega[2], W30, "t = {}", s.t);
    }
    assert!(
        f.samples
            .windows(2)
            .all(|w| w[1].omega_perp < w[0].omega_perp)
    );
    assert!(f.samples.last().unwrap().omega_perp < 0.02 * W20);
}

/// Figure 1's right panel: L fixed along lab z, the axis at the constant tilt
/// of the corrected (4.11), φ and ψ advancing as (Ω₂₀/sin θ)ϑ and Ω̃₃₀ϑ.
#[test]
fn eq_4_11_figure_1_axis_keeps_its_tilt_and_precesses_on_the_clock_vartheta() {
    let f = figure(FigureNumber::One);
    let theta = (W20 / (RATIO * W30)).atan();
    assert!((theta - 0.8961).abs() < 1e-4);
    let s0 = &f.samples[0];
    for s in &f.samples {
        let l = Vec3::from(s.l_lab);
        assert!(angle(&l, &Vec3::z()) < 1e-12, "L along z at t = {}", s.t);
        assert!((s.euler[1] - theta).abs() < 1e-12, "t = {}", s.t);
        assert!((angle(&Figure::axis(s), &Vec3::z()) - theta).abs() < 1e-12);
        let r = (1.0 + 2.0 * W20 * W20 * s.t).sqrt();
        let vartheta = (r - 1.0) / (W20 * W20);
        let phi = W20 / theta.sin() * vartheta;
        let psi = (1.0 - RATIO) * W30 * vartheta;
        assert!(
            wrap(s.euler[0] - s0.euler[0] - phi).abs() < 1e-9,
            "phi at t = {}",
            s.t
        );
        assert!(
            wrap(s.euler[2] - s0.euler[2] - psi).abs() < 1e-9,
            "psi at t = {}",
            s.t
        );
        // The rates fall as 1/R: 1/sqrt(t) late.
        let rates = s.euler_rates.unwrap();
        assert!((rates[0] * r - W20 / theta.sin()).abs() < 1e-12);
        assert!((rates[2] * r - (1.0 - RATIO) * W30).abs() < 1e-12);
        assert!(rates[1].abs() < 1e-12);
    }
}

/// Figure 2's orientation has no closed form: check it against an independent
/// method, DOP853 on Ω and the orientation together (not the closed-form Ω the
/// figure uses), started from the figure's own initial orientation.
#[test]
fn eq_4_17_figure_2_orientation_agrees_with_an_independent_integration() {
    let f = figure(FigureNumber::Two);
    let initial = InitialState::new(Vec3::from(FIGURE_OMEGA0), f.initial_euler()).unwrap();
    let options = MethodOptions::default()
        .with_rtol(1e-11)
        .expect("a valid tolerance");
    let mut sim = Simulation::new(
        Model::Reduced(f.top()),
        MethodChoice::Dop853,
        options,
        initial,
        Some(600.0),
    )
    .unwrap();
    for s in f.samples.iter().step_by(60) {
        let other = sim.advance_to(s.t).unwrap();
        let diff: Mat3 = s.rotation_matrix() - other.rotation_matrix();
        assert!(diff.amax() < 1e-7, "t = {}: {:e}", s.t, diff.amax());
    }
}

/// (4.18) in the frame where lab z is L∞: θ → 0 like e^(−t/σ), φ̇ → (I₃/I₁)Ω₃,
/// ψ̇ → Ω̃₃, and L itself settles on z.
#[test]
fn eq_4_18_figure_2_axis_stands_up_along_l_infinity() {
    let f = figure(FigureNumber::Two);
    let sigma = 1.0 / (RATIO * W30).powi(2);
    assert_eq!(f.l_limit, Vec3::z());
    let at = |t: f64| {
        f.samples
            .iter()
            .find(|s| (s.t - t).abs() < 1e-9)
            .expect("a plotted time")
    };
    let (late, later) = (at(400.0), at(600.0));
    let observed = later.euler[1] / late.euler[1];
    let expected = (-200.0 / sigma).exp();
    assert!(
        (observed / expected - 1.0).abs() < 0.02,
        "{observed} against {expected}"
    );
    assert!(later.euler[1] < 0.02 && f.samples[0].euler[1] > 0.89);
    let rates = later.euler_rates.unwrap();
    assert!((rates[0] - RATIO * W30).abs() < 1e-3, "{rates:?}");
    assert!((rates[2] - (1.0 - RATIO) * W30).abs() < 1e-6, "{rates:?}");
    let turn = |s: &spintop::sim::Sample| angle(&Vec3::from(s.l_lab), &Vec3::z());
    // L turns by 0.063 rad in all; by t = 600 ≈ 3.8σ about e^(−3.8) of that is left.
    assert!(turn(later) < 0.03 * turn(&f.samples[0]));
    // The tilt only ever falls.
    assert!(f.samples.windows(2).all(|w| w[1].euler[1] < w[0].euler[1]));
}

/// A small check that the document is XML-shaped: every opened element is
/// closed in order. Returns the element names in document order.
fn elements(doc: &str) -> Vec<String> {
    let mut stack: Vec<String> = Vec::new();
    let mut names = Vec::new();
    let mut rest = doc;
    while let Some(open) = rest.find('<') {
        let close = rest[open..].find('>').expect("every < has its >") + open;
        let tag = &rest[open + 1..close];
        assert!(!tag.contains('<'), "nested < in {tag}");
        if let Some(name) = tag.strip_prefix('/') {
            assert_eq!(stack.pop().as_deref(), Some(name.trim()), "closing {name}");
        } else {
            let name = tag
                .split_whitespace()
                .next()
                .unwrap()
                .trim_end_matches('/')
                .to_string();
            names.push(name.clone());
            if !tag.ends_with('/') {
                stack.push(name);
            }
        }
        rest = &rest[close + 1..];
    }
    assert!(stack.is_empty(), "unclosed: {stack:?}");
    names
}

fn polylines_with(doc: &str, color: &plotters::style::RGBColor) -> Vec<Vec<(f64, f64)>> {
    let stroke = format!("stroke=\"#{:02X}{:02X}{:02X}\"", color.0, color.1, color.2);
    doc.split("<polyline")
        .skip(1)
        .map(|p| &p[..p.find("/>").unwrap()])
        .filter(|p| p.contains(&stroke))
        .map(|p| {
            let points = p.split("points=\"").nth(1).unwrap();
            let points = &points[..points.find('"').unwrap()];
            points
                .split_whitespace()
                .map(|xy| {
                    let (x, y) = xy.split_once(',').unwrap();
                    (x.parse().unwrap(), y.parse().unwrap())
                })
                .collect()
        })
        .collect()
}

#[test]
fn svg_is_well_formed_with_one_curve_per_quantity_and_finite_coordinates() {
    for number in [FigureNumber::One, FigureNumber::Two] {
        let doc = svg(figure(number));
        assert!(doc.starts_with("<svg "), "{}", &doc[..40]);
        assert!(doc.trim_end().ends_with("</svg>"));
        let names = elements(&doc);
        assert_eq!(names[0], "svg");
        assert_eq!(names.iter().filter(|n| *n == "svg").count(), 1);
        // Curves by colour: (a) the hodograph, (b) the tip path, (c) θ(t) in
        // the curve colour; three wall projections and the tip's shadow; the
        // path of L and L∞; the axis at the start and the end; φ̇ and ψ̇.
        for (color, count, what) in [
            (CURVE_COLOR, 3, "hodograph, axis tip, theta"),
            (PROJECTION_COLOR, 4, "three projections and the shadow"),
            (L_COLOR, 2, "L(t) and L_inf"),
            (AXIS_COLOR, 2, "axis at start and end"),
            (PHI_DOT_COLOR, 1, "phi_dot"),
            (PSI_DOT_COLOR, 1, "psi_dot"),
        ] {
            let lines = polylines_with(&doc, &color);
            assert_eq!(lines.len(), count, "figure {number:?}: {what}");
            for line in &lines {
                assert!(line.len() >= 2);
                for &(x, y) in line {
                    assert!(x.is_finite() && y.is_finite());
                    assert!(
                        (0.0..=SVG_SIZE.0 as f64).contains(&x)
                            && (0.0..=SVG_SIZE.1 as f64).contains(&y),
                        "({x}, {y}) off the canvas"
                    );
                }
            }
        }
        // The hodograph is drawn through every plotted point.
        let hodograph = &polylines_with(&doc, &CURVE_COLOR)[0];
        assert_eq!(hodograph.len(), figure(number).samples.len());
        // No NaN or infinity anywhere in the document.
        assert!(!doc.contains("NaN") && !doc.contains("inf\""));
    }
}

#[test]
fn ascii_names_the_figure_and_draws_every_chart() {
    for number in [FigureNumber::One, FigureNumber::Two] {
        let text = ascii(figure(number));
        assert!(text.starts_with(&format!("Figure {}: ", number.number())));
        assert_eq!(text.matches("Hodograph projected on the plane").count(), 3);
        for chart in ["The top in space", "theta(t)", "phi_dot(t)"] {
            assert!(text.contains(chart), "{chart}");
        }
        assert!(text.chars().any(|c| ('\u{2801}'..='\u{28ff}').contains(&c)));
    }
}

/// The test's own Euler round trip: the figure's initial orientation, as
/// angles, rebuilds the same matrix (so the independent run above starts where
/// the figure starts).
#[test]
fn figure_2_initial_orientation_round_trips_through_euler_angles() {
    let f = figure(FigureNumber::Two);
    let back = f.initial_euler().to_rotation();
    assert!((back - f.initial_rotation).amax() < 1e-14);
    let _: EulerAngles = f.initial_euler();
    assert!((f.samples[0].rotation_matrix() - f.initial_rotation).amax() < 1e-15);
}
