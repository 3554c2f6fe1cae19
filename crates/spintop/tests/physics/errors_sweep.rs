//! Every error a top scene prints, checked against the truth over a sweep
//! (issue 46): the symmetric top with `model = "auto"`, over I₃/I₁,
//! directions of Ω₀, τ|Ω₀| up to 1, horizons up to 10⁶ τ and rtol down to
//! 1e-14. The truth is the physical solution of (3.4) by the invariance
//! equation of its slow manifold ([`crate::physics::invariance`], written from the
//! derivation and checked against mpmath's backward shooting), and the
//! truncated model's closed form written here.
//!
//! Checked, for every scene: the printed `error` of the answer (Ω relative
//! to |Ω₀|, the orientation in radians) and, in `chosen.estimates`, the
//! estimated errors of the truncated and the reduced models over the run.
//! Each is never below the real error, and within 10 times it wherever the
//! real error stands above rounding (the `rounding` the answer prints, and
//! 1e-13 for the model estimates).
//!
//! The coarse grid runs in `cargo test`; the long one is
//! `cargo test -p spintop-tests --test core errors_sweep -- --ignored`.

use crate::physics::invariance::{Manifold, Reference, angle_between, truncated};
use serde_json::Value;
use spintop::math::{Mat3, Real, Vec3};
use spintop::physics::euler_angles::EulerAngles;

/// One scene of the sweep.
#[derive(Clone, Copy, Debug)]
pub struct Case {
    pub ratio: Real,
    /// Angle of Ω₀ from the symmetry axis.
    pub theta: Real,
    /// τ|Ω₀|.
    pub strength: Real,
    /// The last time, τ.
    pub t_end: Real,
    pub rtol: Real,
}

impl Case {
    pub fn omega0(&self) -> Vec3 {
        let (s, c) = self.theta.sin_cos();
        let (s, c) = if self.theta == std::f64::consts::FRAC_PI_2 {
            (1.0, 0.0)
        } else {
            (s, c)
        };
        Vec3::new(0.6 * s, 0.8 * s, c) * self.strength
    }

    pub fn times(&self) -> Vec<Real> {
        // Evenly spaced, and a few early ones (most happens early).
        let mut t: Vec<Real> = (0..=8).map(|j| self.t_end * j as Real / 8.0).collect();
        t.extend([0.01, 0.05, 0.2].map(|f| f * self.t_end));
        t.sort_by(Real::total_cmp);
        t
    }
}

/// A symmetric top's scene: the top, its times, its rtol and its model.
#[derive(Clone, Debug)]
pub struct Scene {
    pub ratio: Real,
    pub omega0: Vec3,
    pub times: Vec<Real>,
    pub rtol: Real,
    /// `auto`, `truncated`, `reduced` or `full`.
    pub model: &'static str,
}

impl Scene {
    pub fn new(ratio: Real, omega0: Vec3, times: Vec<Real>, rtol: Real) -> Self {
        Self {
            ratio,
            omega0,
            times,
            rtol,
            model: "auto",
        }
    }

    pub fn text(&self) -> String {
        let w = self.omega0;
        let times: Vec<String> = self.times.iter().map(|t| format!("{t:e}")).collect();
        format!(
            "[scene]\nname = \"sweep\"\nkind = \"top\"\ndescription = \"Issue 46 sweep.\"\n\n[top]\nmodel = \"{}\"\nratio = {:e}\nomega = [{:e}, {:e}, {:e}]\neuler = [0.3, 0.7, 0.1]\n\n[solve]\ntimes = [{}]\nrtol = {:e}\n",
            self.model,
            self.ratio,
            w.x,
            w.y,
            w.z,
            times.join(", "),
            self.rtol
        )
    }
}

fn num(v: &Value) -> Real {
    v.as_f64().unwrap_or_else(|| panic!("a number: {v}"))
}

fn rotation(v: &Value) -> Mat3 {
    let r: Vec<Real> = v
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|row| row.as_array().unwrap().iter().map(num))
        .collect();
    Mat3::from_row_slice(&r)
}

/// What one scene printed and how far that was from the truth.
#[derive(Debug, Default)]
pub struct Outcome {
    pub lines: Vec<String>,
    pub bad: Vec<String>,
    /// The answer, as JSON (`None` when the scene was refused).
    pub json: Option<Value>,
}

/// What the reference itself may be off by, in Ω relative to |Ω₀| and in
/// the orientation in radians: below these a real error is not resolved.
/// Measured: the reference against itself at half its steps (Ω 2e-16, the
/// orientation 1.3e-13), and its orientation against spintop's reduced
/// model (which shares no code with it) and spintop's physical solution,
/// which show the same pattern in time to 1.1e-12 rad at τ|Ω₀| = 0.3 and
/// T = τ over the coarse grid.
const REFERENCE_OMEGA: Real = 1e-14;
const REFERENCE_ORIENTATION: Real = 2e-12;

impl Outcome {
    /// real ≤ claimed (to the reference's own accuracy `resolved`); claimed
    /// ≤ 10 real where real is above `rounding` and `resolved`.
    fn check(&mut self, what: &str, real: Real, claimed: Real, rounding: Real, resolved: Real) {
        let line = format!("{what}: real {real:.2e} printed {claimed:.2e}");
        let floor = rounding.max(resolved);
        if real > claimed + resolved || (real > floor && claimed > 10.0 * real) || claimed.is_nan()
        {
            self.bad.push(line.clone());
        }
        self.lines.push(line);
    }
}

/// Answer the case's scene and check every printed error.
pub fn run_case(case: &Case) -> Outcome {
    run_scene(
        &format!("{case:?}"),
        &Scene::new(case.ratio, case.omega0(), case.times(), case.rtol),
    )
}

/// Answer a scene and check every printed error against the reference.
pub fn run_scene(tag: &str, case: &Scene) -> Outcome {
    let mut out = Outcome::default();
    let t_end = case.times.last().copied().unwrap_or(0.0);
    let scene = match spintop::scene::parse(&case.text(), "sweep.toml") {
        Ok(s) => s,
        Err(e) => {
            // A refusal before the run must name the rtol it can meet (or
            // the times): it is not a failure of a printed error.
            out.lines.push(format!("{tag}: refused: {e}"));
            assert!(
                e.message.contains("rtol") || e.message.contains("times"),
                "{tag}: {e}"
            );
            return out;
        }
    };
    let report = spintop::scene::answer::answer(&scene)
        .unwrap_or_else(|e| panic!("{tag}: the answer failed: {e}"));
    let v = serde_json::to_value(&report).unwrap();
    out.json = Some(v.clone());
    let omega0 = case.omega0;
    let scale = omega0.norm();
    let times = &case.times;
    let o0 = EulerAngles::new(0.3, 0.7, 0.1).to_rotation();
    let physical = Reference::new(Manifold::Physical, case.ratio, 1.0, omega0, t_end, 1.0);
    let truth_o = physical.orientations(&o0, times);
    let error = &v["error"];
    assert!(
        !error.is_null(),
        "{tag}: no error printed: {}",
        &v.to_string()[..2000.min(v.to_string().len())]
    );
    let rounding = num(&error["rounding"]);
    let model = v["model"].as_str().unwrap().to_string();
    out.lines
        .push(format!("{tag}: model {model}, method {}", v["method"]));
    // The printed samples.
    let samples = v["samples"].as_array().unwrap();
    assert_eq!(samples.len(), times.len(), "{tag}");
    let (mut real_w, mut real_o) = (0.0 as Real, 0.0 as Real);
    for (s, (&t, o_true)) in samples.iter().zip(times.iter().zip(&truth_o)) {
        let w: Vec<Real> = s["omega"].as_array().unwrap().iter().map(num).collect();
        let w = Vec3::new(w[0], w[1], w[2]);
        real_w = real_w.max((w - physical.omega(t)).norm() / scale);
        if !s["rotation"].is_null() {
            real_o = real_o.max(angle_between(&rotation(&s["rotation"]), o_true));
        }
    }
    out.check(
        &format!("{tag} Omega"),
        real_w,
        num(&error["omega"]),
        rounding,
        REFERENCE_OMEGA,
    );
    if !error["orientation"].is_null() {
        out.check(
            &format!("{tag} orientation"),
            real_o,
            num(&error["orientation"]),
            num(&error["orientation_rounding"]),
            REFERENCE_ORIENTATION,
        );
    }
    // The estimates of the two lighter models, over a fine grid of the run.
    let est = &v["chosen"]["estimates"];
    if !est.is_null() {
        let grid: Vec<Real> = (0..=400).map(|j| t_end * j as Real / 400.0).collect();
        let reduced = Reference::new(Manifold::Reduced, case.ratio, 1.0, omega0, t_end, 1.0);
        let truth_grid = physical.orientations(&o0, &grid);
        let reduced_o = reduced.orientations(&o0, &grid);
        let (mut tw, mut to, mut rw, mut ro) = (0.0 as Real, 0.0 as Real, 0.0 as Real, 0.0 as Real);
        for (j, &t) in grid.iter().enumerate() {
            let w = physical.omega(t);
            let (wt, ot) = truncated(case.ratio, 1.0, omega0, &o0, t);
            tw = tw.max((wt - w).norm() / scale);
            to = to.max(angle_between(&ot, &truth_grid[j]));
            rw = rw.max((reduced.omega(t) - w).norm() / scale);
            ro = ro.max(angle_between(&reduced_o[j], &truth_grid[j]));
        }
        let floor = 1e-13;
        let (wf, of) = (REFERENCE_OMEGA, REFERENCE_ORIENTATION);
        let omega_of = |m: &str| num(&est[m]["omega"]);
        out.check(
            &format!("{tag} truncated Omega"),
            tw,
            omega_of("truncated"),
            floor,
            wf,
        );
        out.check(
            &format!("{tag} reduced Omega"),
            rw,
            omega_of("reduced"),
            floor,
            wf,
        );
        if !est["truncated"]["orientation"].is_null() {
            let c = num(&est["truncated"]["orientation"]);
            out.check(&format!("{tag} truncated orientation"), to, c, floor, of);
        }
        if !est["reduced"]["orientation"].is_null() {
            let c = num(&est["reduced"]["orientation"]);
            out.check(&format!("{tag} reduced orientation"), ro, c, floor, of);
        }
    }
    out
}

/// The grid: every combination of the lists.
pub fn sweep(
    ratios: &[Real],
    thetas: &[Real],
    strengths: &[Real],
    t_ends: &[Real],
    rtols: &[Real],
) -> Outcome {
    let mut all = Outcome::default();
    for &ratio in ratios {
        for &theta in thetas {
            for &strength in strengths {
                for &t_end in t_ends {
                    for &rtol in rtols {
                        let case = Case {
                            ratio,
                            theta,
                            strength,
                            t_end,
                            rtol,
                        };
                        let o = run_case(&case);
                        all.lines.extend(o.lines);
                        all.bad.extend(o.bad);
                    }
                }
            }
        }
    }
    all
}

/// Print the outcome and fail on any printed error broken.
fn assert_all_hold(o: &Outcome) {
    for l in &o.lines {
        println!("{l}");
    }
    assert!(
        o.bad.is_empty(),
        "{} printed errors broken:\n{}",
        o.bad.len(),
        o.bad.join("\n")
    );
}

/// Issue 46, (5): the coarse grid, every printed error true and within 10×.
#[test]
fn eq_3_4_every_printed_error_holds_on_a_coarse_grid() {
    let o = sweep(
        &[0.05, 1.5],
        &[0.8, std::f64::consts::FRAC_PI_2],
        &[0.01, 1.0],
        &[100.0],
        &[1e-8, 1e-12],
    );
    assert_all_hold(&o);
}

/// Issue 46, (5): the long sweep, I₃/I₁ from 0.05 to 1.5, Ω₀ near the axis
/// to across it, τ|Ω₀| to 1, horizons to 10⁶ τ, rtol 1e-4 to 1e-14.
///
/// NOTE: not yet part of CI's end-to-end tier: its 432 scenes have not been
/// run to the end (the one attempt, in a debug build on a loaded machine,
/// was stopped at 40 minutes), and issue 46 still lists cases it would
/// catch (the general top at rtol 1e-10, the secular claim). It runs with
/// `SPINTOP_LONG_SWEEP=1 cargo test -p spintop-tests --test core long_sweep -- --ignored`.
#[test]
#[ignore = "end-to-end, opt-in: the long sweep of issue 46 (SPINTOP_LONG_SWEEP=1)"]
fn eq_3_4_every_printed_error_holds_over_the_long_sweep() {
    if std::env::var_os("SPINTOP_LONG_SWEEP").is_none() {
        eprintln!("the long sweep runs with SPINTOP_LONG_SWEEP=1 (issue 46)");
        return;
    }
    let o = sweep(
        &[0.05, 0.4, 1.5],
        &[0.05, 0.8, std::f64::consts::FRAC_PI_2],
        &[0.01, 0.3, 1.0],
        &[1.0, 100.0, 1e4, 1e6],
        &[1e-4, 1e-8, 1e-12, 1e-14],
    );
    assert_all_hold(&o);
}
