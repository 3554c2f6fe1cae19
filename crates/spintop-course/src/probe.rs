//! The probe: the student's function of time sampled for `spintop learn`,
//! which draws it on the chapter's chart against the reference. It is a
//! picture, not a grade: nothing here decides whether an assignment passes.

use std::path::Path;
use std::process::Command;

/// A function of time of the course, sampled on the student's code for
/// `spintop learn`, which draws it against the reference on the chapter's
/// chart (the probe `lessons/tests/probe.rs`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProbeSpec {
    /// The assignment's function.
    pub function: &'static str,
    /// I₃/I₁.
    pub ratio: f64,
    /// τ.
    pub tau: f64,
    /// Ω₀.
    pub omega0: [f64; 3],
    /// The samples span [0, t_end].
    pub t_end: f64,
    /// Intervals between samples.
    pub samples: usize,
}

impl ProbeSpec {
    /// The probe of the chapter titled `title`, if it has one: the closed
    /// form of its model at the scene's parameters (the paper's top,
    /// I₃/I₁ = 2/5, Ω₀ = (0, 0.1, 0.2)).
    pub fn for_chapter(title: &str) -> Option<Self> {
        let (function, t_end) = if title.starts_with("Section 4.1") {
            ("truncated_closed_form", 400.0)
        } else if title.starts_with("Section 4.2") {
            ("reduced_closed_form", 200.0)
        } else {
            return None;
        };
        Some(Self {
            function,
            ratio: spintop::figure::FIGURE_RATIO,
            tau: 1.0,
            omega0: spintop::figure::FIGURE_OMEGA0,
            t_end,
            samples: 200,
        })
    }

    /// The request, as `SPINTOP_PROBE` carries it.
    pub fn request(&self) -> String {
        let [w1, w2, w3] = self.omega0;
        format!(
            "{} {} {} {w1} {w2} {w3} {} {}",
            self.function, self.ratio, self.tau, self.t_end, self.samples
        )
    }
}

/// What the probe found.
#[derive(Debug, Clone, PartialEq)]
pub enum Probed {
    /// The student's Ω(t) at the sample times, as `(t, [Ω₁, Ω₂, Ω₃])`.
    Samples(Vec<(f64, [f64; 3])>),
    /// The function panicked (a `todo!()` stub, or a crash): its message.
    Panicked(String),
}

/// Reads the probe's output.
pub fn parse_probe(output: &str) -> Result<Probed, String> {
    let mut samples = Vec::new();
    for line in output.lines() {
        if let Some(msg) = line.strip_prefix("probe: panicked: ") {
            return Ok(Probed::Panicked(msg.to_string()));
        }
        if let Some(msg) = line.strip_prefix("probe: ") {
            return Err(msg.to_string());
        }
        if let Some(rest) = line.strip_prefix("probe ") {
            let v: Vec<f64> = rest
                .split_whitespace()
                .filter_map(|w| w.parse().ok())
                .collect();
            if let [t, a, b, c] = v[..] {
                samples.push((t, [a, b, c]));
            }
        }
    }
    if samples.is_empty() {
        let first_error = output
            .lines()
            .find(|l| l.starts_with("error"))
            .unwrap_or("the probe printed nothing");
        return Err(first_error.to_string());
    }
    Ok(Probed::Samples(samples))
}

/// Runs the probe of `spec` on the lessons crate in `dir` (a cargo child
/// process; about a second once built).
pub fn probe(dir: &Path, spec: &ProbeSpec) -> Result<Probed, String> {
    let mut cmd = Command::new(super::find_cargo().map_err(|e| e.to_string())?);
    cmd.current_dir(dir)
        .arg("test")
        .arg("--manifest-path")
        .arg(dir.join("Cargo.toml"))
        .args(["--quiet", "--color", "never", "--test", "probe"])
        .args(["--", "--ignored", "--nocapture", "--exact", "probe"])
        .env("SPINTOP_PROBE", spec.request())
        .env("RUST_BACKTRACE", "0");
    let out = cmd.output().map_err(|e| format!("cannot run cargo: {e}"))?;
    parse_probe(&format!(
        "{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lessons_dir;

    #[test]
    fn the_probe_of_a_chapter_is_read_back() {
        assert!(ProbeSpec::for_chapter("Section 2: two laws").is_none());
        let spec = ProbeSpec::for_chapter("Section 4.2: the reduced top").unwrap();
        assert_eq!(
            spec.request(),
            "reduced_closed_form 0.4 1 0 0.1 0.2 200 200"
        );
        let out = "running 1 test\nprobe 0e0 0e0 1e-1 2e-1\nprobe 1e0 1e-2 9e-2 2e-1\ntest probe ... ok\n";
        assert_eq!(
            parse_probe(out),
            Ok(Probed::Samples(vec![
                (0.0, [0.0, 0.1, 0.2]),
                (1.0, [0.01, 0.09, 0.2])
            ]))
        );
        assert_eq!(
            parse_probe("probe: panicked: not yet implemented: Eq. (4.7)\n"),
            Ok(Probed::Panicked("not yet implemented: Eq. (4.7)".into()))
        );
        assert!(parse_probe("error[E0308]: mismatched types\n").is_err());
    }

    #[test]
    #[ignore = "end-to-end: builds the lessons with the solutions"]
    fn the_probe_samples_the_reference_solution() {
        // The instructor's solution through the real probe: cargo runs it.
        let spec = ProbeSpec::for_chapter("Section 4.2").unwrap();
        let dir = lessons_dir(crate::repository());
        let probed = probe(&dir, &spec).unwrap();
        // Without the solutions feature the stub answers: not started.
        assert!(
            matches!(probed, Probed::Panicked(ref m) if m.contains("not yet implemented")),
            "{probed:?}"
        );
    }
}
