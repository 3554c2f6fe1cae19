//! Every top scene of the catalogue opens in the live view as `spintop run`
//! starts it: Ω₀ and O(0) (the scene's Euler angles, where it gives them)
//! at t = 0, and the same Ω and orientation a few steps on, compared with
//! the core's own run of the scene through the library.

use spintop::scene::answer::{Answer, TopRun, answer};
use spintop::scene::{Body, catalogue};
use spintop_app::live::stepper::TICK;
use spintop_app::live::{App, Settings};

fn close(a: &[f64], b: &[f64], tol: f64) -> bool {
    a.iter()
        .zip(b)
        .all(|(x, y)| (x - y).abs() <= tol * (1.0 + y.abs()))
}

#[test]
fn every_top_scene_starts_where_spintop_run_starts_it() {
    let mut compared = 0;
    for entry in catalogue::CATALOGUE {
        let scene = entry.scene().unwrap();
        let Body::Top(top) = &scene.body else {
            continue;
        };
        let Ok(report) = answer(&scene) else { continue };
        let Answer::Top(ans) = report.answer else {
            continue;
        };
        let TopRun::Full(out) = &ans.run else {
            continue;
        };
        let (settings, _) = match Settings::for_scene(&scene, None) {
            Ok(s) => s,
            Err(e) => {
                // A scene the view cannot show is refused saying what can.
                assert!(e.to_string().contains("spintop run"), "{}: {e}", entry.name);
                continue;
            }
        };
        let mut app = App::new(settings).unwrap();
        let first = &out.samples[0];
        assert_eq!(first.t, 0.0);
        for c in app.columns() {
            let s = c.start();
            assert!(close(&s.omega, &first.omega, 1e-12), "{}: Ω", entry.name);
            for (row, want) in s.rotation.iter().zip(&first.rotation) {
                assert!(close(row, want, 1e-12), "{}: O(0)", entry.name);
            }
            assert_eq!(
                s.euler_rates.is_none(),
                first.euler_rates.is_none(),
                "{}: the pole",
                entry.name
            );
        }
        // A few steps on: the column of the scene's own model, at the
        // scene's first time after 0 when it is near.
        if let Some(later) = out.samples.iter().find(|s| s.t > 0.0 && s.t <= 10.0) {
            app.advance_ticks((later.t / TICK).round() as u64);
            let column = app
                .columns()
                .iter()
                .find(|c| *c.model() == top.model)
                .unwrap_or_else(|| panic!("{}: no column of its model", entry.name));
            let now = column.current();
            assert!(
                (now.t - later.t).abs() < 1e-9,
                "{}: t = {}",
                entry.name,
                now.t
            );
            assert!(close(&now.omega, &later.omega, 1e-6), "{}: Ω", entry.name);
            for (row, want) in now.rotation.iter().zip(&later.rotation) {
                assert!(close(row, want, 1e-6), "{}: O({})", entry.name, later.t);
            }
        }
        compared += 1;
    }
    assert!(compared >= 8, "only {compared} scenes compared");
}

/// `erratum-5-generic-frame` shows the angle of e₃ from lab z, its subject, and `euler-pole` the
/// pole, on the screen.
#[test]
fn a_scene_s_own_frame_is_on_the_screen() {
    use ratatui::{Terminal, backend::TestBackend};
    for (name, want) in [
        ("erratum-5-generic-frame", "e₃∠z = 1"),
        ("euler-pole", "— (pole)"),
    ] {
        let scene = catalogue::find(name).unwrap().scene().unwrap();
        let (settings, _) = Settings::for_scene(&scene, None).unwrap();
        let mut app = App::new(settings).unwrap();
        app.apply(spintop_app::live::Command::Resize(200, 60));
        let mut terminal = Terminal::new(TestBackend::new(200, 60)).unwrap();
        terminal
            .draw(|f| spintop_app::tui::view::draw(f, &app))
            .unwrap();
        let screen = terminal.backend().to_string();
        assert!(screen.contains(want), "{name}: no `{want}`:\n{screen}");
        assert!(!screen.contains("lab z ∥ L₀"), "{name}:\n{screen}");
        // θ is not a second name on this screen: the title's angle is from
        // lab z, the numbers' tilt from L.
        assert!(!screen.contains("θ = "), "{name}:\n{screen}");
    }
}
