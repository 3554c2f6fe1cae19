use crate::physics::invariance::{Manifold, Reference, angle_between};
use spintop::math::{Real, Vec3};
use spintop::physics::euler_angles::EulerAngles;
use spintop::physics::symmetric_top::SymmetricTop;
use spintop::sim::{InitialState, MethodChoice, MethodOptions, Model, Simulation};

fn errs(ratio: Real, omega0: Vec3, times: &[Real], rtol: Real) {
    let t_max = *times.last().unwrap();
    let r = Reference::new(Manifold::Physical, ratio, 1.0, omega0, t_max, 1.0);
    let r2 = Reference::new(Manifold::Physical, ratio, 1.0, omega0, t_max, 0.5);
    let o0 = EulerAngles::new(0.3, 0.7, 0.1).to_rotation();
    let ro = r.orientations(&o0, times);
    let ro2 = r2.orientations(&o0, times);
    let top = SymmetricTop::new(ratio, 1.0).unwrap();
    let init = InitialState::new(omega0, EulerAngles::new(0.3, 0.7, 0.1)).unwrap();
    let opts = MethodOptions::default().with_rtol(rtol).unwrap();
    let mut sim = Simulation::new(
        Model::Full(top),
        MethodChoice::Auto,
        opts,
        init,
        Some(t_max),
    )
    .unwrap();
    let (mut eo, mut ea, mut self_o, mut self_a) =
        (0.0 as Real, 0.0 as Real, 0.0 as Real, 0.0 as Real);
    for (j, &t) in times.iter().enumerate() {
        let s = *sim.advance_to(t).unwrap();
        let w = r.omega(t);
        let w2 = r2.omega(t);
        eo = eo.max((s.omega_vec() - w).norm() / omega0.norm());
        self_o = self_o.max((w2 - w).norm() / omega0.norm());
        ea = ea.max(angle_between(&s.rotation_matrix(), &ro[j]));
        self_a = self_a.max(angle_between(&ro2[j], &ro[j]));
    }
    println!(
        "ratio {ratio} omega0 {omega0:?} T {t_max} rtol {rtol:e}: omega err {eo:.2e} orient {ea:.2e} (ref self {self_o:.1e} {self_a:.1e}) steps {}",
        sim.stats().steps
    );
}

#[test]
#[ignore]
fn scratch_ref_conv() {
    let ts = |t: Real, n: usize| {
        (0..=n)
            .map(|j| t * j as Real / n as Real)
            .collect::<Vec<_>>()
    };
    let o0 = EulerAngles::new(0.3, 0.7, 0.1).to_rotation();
    for (ratio, w, t) in [
        (0.05, Vec3::new(0.0, 0.0003, 0.3), 1.33e3),
        (0.05, Vec3::new(0.0, 0.0003, 0.3), 1.33e4),
        (0.4, Vec3::new(0.0, 0.1, 0.2), 100.0),
        (0.05, Vec3::new(0.0, 0.0003, 0.3), 1.33e5),
        (0.4, Vec3::new(0.0, 0.3, 0.0), 11.1),
        (1.5, Vec3::new(0.5, 0.2, 0.8), 50.0),
    ] {
        let times = ts(t, 10);
        let rs: Vec<_> = [1.0, 0.5, 0.25]
            .iter()
            .map(|&sc| Reference::new(Manifold::Physical, ratio, 1.0, w, t, sc))
            .collect();
        let os: Vec<_> = rs.iter().map(|r| r.orientations(&o0, &times)).collect();
        let d = |a: usize, b: usize| {
            (0..times.len())
                .map(|j| angle_between(&os[a][j], &os[b][j]))
                .fold(0.0 as Real, Real::max)
        };
        let dw = |a: usize, b: usize| {
            times
                .iter()
                .map(|&t| (rs[a].omega(t) - rs[b].omega(t)).norm())
                .fold(0.0 as Real, Real::max)
        };
        println!(
            "{ratio} {w:?}: orient d01 {:.2e} d12 {:.2e}; omega {:.2e} {:.2e}",
            d(0, 1),
            d(1, 2),
            dw(0, 1),
            dw(1, 2)
        );
    }
}

#[test]
#[ignore]
fn scratch_issue46() {
    let ts = |t: Real, n: usize| {
        (0..=n)
            .map(|j| t * j as Real / n as Real)
            .collect::<Vec<_>>()
    };
    for rtol in [1e-8, 1e-10, 1e-12] {
        errs(
            0.4,
            Vec3::new(0.0, 0.3, 0.0),
            &[0.0, 2.22, 6.67, 8.89, 11.1],
            rtol,
        );
    }
    for rtol in [1e-8, 1e-12, 1e-14] {
        errs(0.05, Vec3::new(0.212, 0.212, 0.0), &ts(0.222, 10), rtol);
    }
    for t in [1.33e3, 1.33e4, 1.33e5] {
        errs(0.05, Vec3::new(0.0, 0.0003, 0.3), &ts(t, 10), 1e-10);
        errs(0.05, Vec3::new(0.0, 0.0, 0.3), &ts(t, 10), 1e-10);
    }
    errs(0.4, Vec3::new(0.0, 0.1, 0.2), &ts(100.0, 10), 1e-10);
}

#[test]
#[ignore]
fn scratch_ref_long() {
    let o0 = EulerAngles::new(0.3, 0.7, 0.1).to_rotation();
    let (ratio, w, t) = (0.05, Vec3::new(0.0, 0.0003, 0.3), 1.33e5);
    let times: Vec<Real> = (0..=20).map(|j| t * j as Real / 20.0).collect();
    let rs: Vec<_> = [1.0, 0.5, 0.25]
        .iter()
        .map(|&sc| Reference::new(Manifold::Physical, ratio, 1.0, w, t, sc))
        .collect();
    let os: Vec<_> = rs.iter().map(|r| r.orientations(&o0, &times)).collect();
    for j in 0..times.len() {
        let (s, _, _) = rs[0].s_at(times[j]);
        println!(
            "t {:.4e} s {s:.3} d01 {:.2e} d12 {:.2e}",
            times[j],
            angle_between(&os[0][j], &os[1][j]),
            angle_between(&os[1][j], &os[2][j])
        );
    }
}

#[test]
#[ignore]
fn scratch_ref_values() {
    for (ratio, w, ts) in [
        (0.4, Vec3::new(0.0, 0.3, 0.0), vec![2.22, 6.67, 11.1]),
        (0.4, Vec3::new(0.0, 0.1, 0.2), vec![10.0, 50.0]),
        (1.5, Vec3::new(0.5, 0.2, 0.8), vec![1.0, 5.0]),
    ] {
        let r = Reference::new(Manifold::Physical, ratio, 1.0, w, 60.0, 1.0);
        for t in ts {
            let o = r.omega(t);
            println!("{ratio} t {t}: {:.17e} {:.17e}", o.x, o.y);
        }
    }
}

#[test]
#[ignore]
fn scratch_case2() {
    use spintop::sim::physical::physical_solution;
    let (ratio, w) = (0.05, Vec3::new(0.212, 0.212, 0.0));
    let times: Vec<Real> = (0..=10).map(|j| 0.222 * j as Real / 10.0).collect();
    let r = Reference::new(Manifold::Physical, ratio, 1.0, w, 1.0, 1.0);
    let top = SymmetricTop::new(ratio, 1.0).unwrap();
    for rtol in [1e-10, 1e-12, 1e-14] {
        let sol = physical_solution(&top, &w, &times, rtol).unwrap();
        let errs: Vec<String> = times
            .iter()
            .zip(&sol.z)
            .map(|(&t, z)| {
                let o = r.omega(t);
                format!("{:.1e}", (Vec3::new(z.re, z.im, 0.0) - o).norm() / w.norm())
            })
            .collect();
        println!(
            "rtol {rtol:e} shots {} steps {}: {}",
            sol.shots,
            sol.stats.steps,
            errs.join(" ")
        );
    }
}

#[test]
#[ignore]
fn scratch_al() {
    use spintop::integrate::{AdaptiveOptions, Dop853, solve};
    use spintop::math::State;
    use spintop::physics::central::{
        ChargeInField, Potential, abraham_lorentz_oscillator_roots, abraham_lorentz_rhs,
        oscillator_mode,
    };
    let tau0 = 1e-2;
    let q = ChargeInField::new(Potential::Harmonic, tau0).unwrap();
    let (s, _) = abraham_lorentz_oscillator_roots(tau0);
    let (x0, v0) = (
        nalgebra::Vector2::new(1.0, 0.0),
        nalgebra::Vector2::new(0.0, 1.0),
    );
    let (xf, vf, _) = oscillator_mode(s, &x0, &v0, 5.0);
    let y_final = State::<6>::new(xf.x, xf.y, vf.x, vf.y, -xf.x, -xf.y);
    let rhs = |_t: f64, y: &State<6>| abraham_lorentz_rhs(&q, y);
    for rtol in [1e-12, 1.1e-12, 1.2e-12, 0.9e-12, 1e-11] {
        let mut line = String::new();
        for t in [4.9, 4.0, 2.0, 0.0] {
            let mut back = Dop853::new(
                5.0,
                y_final,
                AdaptiveOptions::new(rtol, rtol * 1e-3).unwrap(),
            )
            .unwrap();
            let y = &solve(&mut back, &rhs, &[t]).unwrap()[0];
            let x = nalgebra::Vector2::new(y[0], y[1]);
            let v = nalgebra::Vector2::new(y[2], y[3]);
            let off =
                (nalgebra::Vector2::new(y[4], y[5]) - oscillator_mode(s, &x, &v, 0.0).2).norm();
            line += &format!(" {off:.1e}");
        }
        println!("rtol {rtol:e}:{line}");
    }
}

#[test]
#[ignore]
fn scratch_orient_cmp() {
    use crate::physics::errors_sweep::Case;
    for (ratio, theta, strength, t_end) in [
        (1.5, 0.8, 0.01, 100.0),
        (0.4, std::f64::consts::FRAC_PI_2, 0.01, 1.0),
        (0.4, 0.05, 0.3, 100.0),
    ] {
        let case = Case {
            ratio,
            theta,
            strength,
            t_end,
            rtol: 1e-12,
        };
        let w = case.omega0();
        let times = case.times();
        let o0 = EulerAngles::new(0.3, 0.7, 0.1).to_rotation();
        let top = SymmetricTop::new(ratio, 1.0).unwrap();
        let init = InitialState::new(w, EulerAngles::new(0.3, 0.7, 0.1)).unwrap();
        for (manifold, model) in [
            (Manifold::Reduced, Model::Reduced(top)),
            (Manifold::Physical, Model::Full(top)),
        ] {
            let r = Reference::new(manifold, ratio, 1.0, w, t_end, 0.5);
            let ro = r.orientations(&o0, &times);
            let opts = MethodOptions::default().with_rtol(1e-12).unwrap();
            let mut sim =
                Simulation::new(model, MethodChoice::Auto, opts, init, Some(t_end)).unwrap();
            let mut line = String::new();
            for (j, &t) in times.iter().enumerate() {
                let s = *sim.advance_to(t).unwrap();
                line += &format!(" {:.1e}", angle_between(&s.rotation_matrix(), &ro[j]));
            }
            println!("{ratio} {theta} {strength} {t_end} {manifold:?}:{line}");
        }
    }
}

#[test]
#[ignore]
fn scratch_measured() {
    use spintop::sim::physical::physical_table;
    let (ratio, w, t_end) = (0.4, Vec3::new(0.6, 0.8, 0.0), 1e4);
    let top = SymmetricTop::new(ratio, 1.0).unwrap();
    let r = Reference::new(Manifold::Physical, ratio, 1.0, w, t_end, 1.0);
    for rtol in [1e-12, 1e-10] {
        let opts = MethodOptions::default().with_rtol(rtol).unwrap();
        let table = physical_table(&top, &w, t_end, &opts, 10_000_000).unwrap();
        let mut worst = (0.0, 0.0);
        for j in 0..=2000 {
            let t = t_end * j as Real / 2000.0;
            let e = (table.omega_at(t) - r.omega(t)).norm();
            if e > worst.0 {
                worst = (e, t);
            }
        }
        println!(
            "rtol {rtol:e}: worst {:.2e} at t {}, t_end {} steps {} shots {}",
            worst.0,
            worst.1,
            table.t_end(),
            table.stats.steps,
            table.shots
        );
    }
}

fn scene_outcome(tag: &str, body: &str) {
    let text = format!("[scene]\nname = \"x\"\nkind = \"top\"\ndescription = \"x.\"\n\n{body}");
    match spintop::scene::parse(&text, "x.toml") {
        Err(e) => println!("{tag}: REFUSED {e}"),
        Ok(scene) => match spintop::scene::answer::answer(&scene) {
            Err(e) => println!("{tag}: FAILED {e}"),
            Ok(r) => {
                let v = serde_json::to_value(&r).unwrap();
                let s0 = &v["samples"][0];
                println!(
                    "{tag}: model {} method {} error {} stats {} warnings {} first {}\n   chosen {}",
                    v["model"],
                    v["method"],
                    v["error"],
                    v["stats"],
                    v["warnings"],
                    s0["omega"],
                    v["chosen"]["reason"]
                        .as_str()
                        .unwrap_or("")
                        .chars()
                        .take(400)
                        .collect::<String>()
                );
            }
        },
    }
}

#[test]
#[ignore]
fn scratch_issue_scenes() {
    let s = |tag: &str, body: &str| scene_outcome(tag, body);
    s(
        "trunc-axis",
        "[top]\nmodel = \"auto\"\nratio = 0.665\nomega = [4.3e-6, -9.2e-6, 0.0745]\n\n[solve]\nt_end = 2337.0\nsamples = 11\nrtol = 0.03\n",
    );
    s(
        "secular",
        "[top]\nmodel = \"auto\"\ninertia = [1.0, 1.0, 0.4]\ndipole = [0.0, 0.0, 1.0]\nomega = [6e-5, 3e-5, 7.4e-5]\n\n[solve]\nt_end = 1e11\nsamples = 5\nrtol = 1e-2\n",
    );
    s(
        "tiny",
        "[top]\nmodel = \"auto\"\nratio = 0.4\nomega = [1e-170, 2e-170, 1e-170]\n\n[solve]\nt_end = 10.0\nsamples = 3\n",
    );
    s(
        "first-0.5",
        "[top]\nmodel = \"full\"\nratio = 1.0\nomega = [0.0, 0.6, 0.29]\n\n[solve]\nt_end = 20.0\nsamples = 3\nrtol = 0.5\n",
    );
    s(
        "shoot-a",
        "[top]\nmodel = \"full\"\nratio = 0.4\nomega = [0.0, 0.5, 0.0]\n\n[solve]\nt_end = 100.0\nsamples = 3\nrtol = 0.5\n",
    );
    s(
        "shoot-b",
        "[top]\nmodel = \"full\"\nratio = 1.0\nomega = [0.0, 1.0, 0.0]\n\n[solve]\nt_end = 10.0\nsamples = 3\nrtol = 0.6\n",
    );
    s(
        "shoot-c",
        "[top]\nmodel = \"full\"\nratio = 0.5\nomega = [0.0, 2.0, 0.0]\n\n[solve]\nt_end = 1.0\nsamples = 3\nrtol = 0.5\n",
    );
    s(
        "fig2-times",
        "[top]\nmodel = \"auto\"\nratio = 0.4\nomega = [0.0, 0.1, 0.2]\n\n[solve]\ntimes = [0.0, 1e6, 1e12]\n",
    );
    for t in ["1e9", "1e10", "1e11"] {
        s(
            &format!("asym-{t}"),
            &format!(
                "[top]\nmodel = \"auto\"\ninertia = [1.0, 1.5, 0.8]\ndipole = [0.2, 0.0, 1.0]\nomega = [6e-5, 3e-5, 7.4e-5]\n\n[solve]\nt_end = {t}\nsamples = 5\nrtol = 1e-2\n"
            ),
        );
    }
    for r in ["1e-4", "1e-5"] {
        s(
            &format!("symgen-{r}"),
            &format!(
                "[top]\nmodel = \"auto\"\ninertia = [1.0, 1.0, 0.4]\ndipole = [0.0, 0.0, 1.0]\nomega = [6e-5, 3e-5, 7.4e-5]\n\n[solve]\nt_end = 3e9\nsamples = 5\nrtol = {r}\n"
            ),
        );
    }
    s(
        "gen-1e-10",
        "[top]\nmodel = \"auto\"\ninertia = [0.5, 1.0, 1.2]\ndipole = [0.0, 1.0, 0.0]\nomega = [0.05, 0.01, 0.1]\n\n[solve]\nt_end = 300.0\nsamples = 7\nrtol = 1e-10\n",
    );
    s(
        "free-dop853",
        "[top]\nmodel = \"general\"\ninertia = [1.0, 1.5, 0.8]\ndipole = [1e-4, 0.0, 1e-4]\nomega = [0.1, 0.05, 0.2]\n\n[solve]\nmethod = \"dop853\"\nt_end = 1e5\nsamples = 5\nrtol = 1e-8\n",
    );
    s(
        "free-taylor",
        "[top]\nmodel = \"general\"\ninertia = [1.0, 1.5, 0.8]\ndipole = [1e-4, 0.0, 1e-4]\nomega = [0.1, 0.05, 0.2]\n\n[solve]\nmethod = \"taylor\"\nt_end = 1e5\nsamples = 5\nrtol = 1e-10\n",
    );
    s(
        "strong-tk",
        "[top]\nmodel = \"full\"\nratio = 1.0\nomega = [0.0, 0.001, 1e6]\n\n[solve]\nt_end = 10.0\nsamples = 3\n",
    );
}

#[test]
#[ignore]
fn scratch_measured_fallback() {
    use spintop::sim::measured::symmetric_measured;
    let top = SymmetricTop::new(1.5, 1.0).unwrap();
    let case = crate::physics::errors_sweep::Case {
        ratio: 1.5,
        theta: 0.8,
        strength: 1.0,
        t_end: 1e4,
        rtol: 1e-8,
    };
    let m = symmetric_measured(&top, &case.omega0(), &case.times());
    println!("{m:?}");
}
