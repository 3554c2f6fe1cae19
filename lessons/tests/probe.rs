//! Not a grader: samples your functions of time for `spintop learn`, which
//! draws them on the chapter's chart against the reference. It runs only when
//! asked (`#[ignore]`, and `SPINTOP_PROBE` names the function and its
//! inputs), so `cargo test` never counts it.

use spintop::assignment::Vec3;
use spintop_lessons::ch4;

#[test]
#[ignore = "run by spintop learn with SPINTOP_PROBE set"]
fn probe() {
    let Ok(spec) = std::env::var("SPINTOP_PROBE") else {
        return;
    };
    let words: Vec<&str> = spec.split_whitespace().collect();
    let numbers: Vec<f64> = words
        .iter()
        .skip(1)
        .filter_map(|w| w.parse().ok())
        .collect();
    let [ratio, tau, w1, w2, w3, t_end, samples] = numbers[..] else {
        println!("probe: bad request {spec}");
        return;
    };
    let function: fn(f64, f64, Vec3, f64) -> Vec3 = match words.first() {
        Some(&"truncated_closed_form") => ch4::truncated_closed_form,
        Some(&"reduced_closed_form") => ch4::reduced_closed_form,
        _ => {
            println!("probe: no such function in {spec}");
            return;
        }
    };
    // A todo!() or a crash is reported in one line, not as a backtrace.
    std::panic::set_hook(Box::new(|_| {}));
    let n = samples as usize;
    for i in 0..=n {
        let t = t_end * i as f64 / n as f64;
        match std::panic::catch_unwind(|| function(ratio, tau, Vec3::new(w1, w2, w3), t)) {
            Ok(w) => println!("probe {t:e} {:e} {:e} {:e}", w.x, w.y, w.z),
            Err(payload) => {
                let msg = payload
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| payload.downcast_ref::<String>().cloned())
                    .unwrap_or_default();
                println!("probe: panicked: {msg}");
                return;
            }
        }
    }
}
