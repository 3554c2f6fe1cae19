//! Lesson for Section 3: the kinematics of a rigid top, the truncated ALE
//! (3.3) for any top, and the Euler angles (3.5).
//!
//! Run it: `cargo run --release --example ch3_equations_of_motion`
//!
//! The book shows this program's output; `tests/project/book.rs` checks that what the
//! book shows is what the program prints.

use spintop::math::{Vec3, orthonormality_error, vee};
use spintop::physics::euler_angles::{EulerAngles, EulerRates, body_rate_from_euler, euler_rates};
use spintop::physics::general_top::GeneralTop;
use spintop::physics::rigid_body::{energy, lab_velocity};
use spintop::physics::symmetric_top::{SymmetricTop, truncated_ale_rhs, truncated_orientation};
use spintop::plot::{Series, chart};
use spintop::sim::{InitialState, MethodChoice, MethodOptions, Model, Simulation};
use std::io::{self, Write};

/// Print the lesson to `out`: its four parts in order.
pub fn run(out: &mut dyn Write) -> io::Result<()> {
    writeln!(
        out,
        "Section 3: equations of motion of a free polarized top\n"
    )?;
    kinematics(out)?;
    let omega = general_reduces_to_symmetric(out)?;
    euler_convention(out, &omega)?;
    orientation_on_so3(out)
}

/// (3.1): the velocity of a body point, against a central difference.
fn kinematics(out: &mut dyn Write) -> io::Result<()> {
    // ANCHOR: kinematics
    // (3.1): a body point rho moves with v = O (Omega x rho). Check it against a
    // central difference of r(t) = O(t) rho along the truncated top's motion.
    let top = SymmetricTop::figure();
    let omega0 = Vec3::new(0.02, 0.1, 0.2);
    let o0 = EulerAngles::new(0.3, 0.9, -0.2).to_rotation();
    let rho = Vec3::new(0.5, -0.2, 1.0);
    let (t, h) = (40.0, 1e-4);
    let r = |t: f64| truncated_orientation(&top, &omega0, &o0, t) * rho;
    let v_fd = (r(t + h) - r(t - h)) / (2.0 * h);
    let omega = spintop::physics::symmetric_top::truncated_closed_form(&top, &omega0, t);
    let v = lab_velocity(&truncated_orientation(&top, &omega0, &o0, t), &omega, &rho);
    // ANCHOR_END: kinematics
    writeln!(
        out,
        "(3.1) at t = {t}: v = O(Omega x rho) = [{:.6}, {:.6}, {:.6}]",
        v.x, v.y, v.z
    )?;
    writeln!(
        out,
        "      central difference of O(t)rho:  |difference| below 1e{}",
        (v - v_fd).norm().log10().ceil()
    )?;
    Ok(())
}

/// (3.3) for a general top, fed a symmetric one, against (4.2)-(4.4); returns
/// the body rate it compared them at.
fn general_reduces_to_symmetric(out: &mut dyn Write) -> io::Result<Vec3> {
    // ANCHOR: general_reduces_to_symmetric
    // (3.3) for a general top, fed a symmetric one (I2 = I1, d along e3, tau = d^2/I1 = 1),
    // is the symmetric top's (4.2)-(4.4).
    let top = SymmetricTop::figure();
    let general =
        GeneralTop::new(Vec3::new(1.0, 1.0, 0.4), Vec3::new(0.0, 0.0, 1.0)).expect("a rigid body");
    let w = Vec3::new(0.05, 0.1, 0.2);
    let a = general.truncated_ale_rhs(&w);
    let b = truncated_ale_rhs(&top, &w);
    // ANCHOR_END: general_reduces_to_symmetric
    writeln!(
        out,
        "\n(3.3) with symmetric inputs: dOmega/dt = [{:.6e}, {:.6e}, {:.6e}]",
        a.x, a.y, a.z
    )?;
    writeln!(
        out,
        "(4.2)-(4.4):                 dOmega/dt = [{:.6e}, {:.6e}, {:.6e}]",
        b.x, b.y, b.z
    )?;
    Ok(w)
}

/// (3.5) gives the body rate, not the lab rate; at the pole it has no
/// answer for the body rate `w`.
fn euler_convention(out: &mut dyn Write, w: &Vec3) -> io::Result<()> {
    // ANCHOR: euler_convention
    // (3.5) holds for O = Rz(phi) Rx(theta) Rz(psi) with the BODY rate Omega^ = O^T dO/dt.
    let angles = |t: f64| EulerAngles::new(0.2 + 0.3 * t, 1.0 - 0.1 * t, 0.5 + 0.7 * t);
    let rates = EulerRates {
        phi_dot: 0.3,
        theta_dot: -0.1,
        psi_dot: 0.7,
    };
    let (t, h) = (1.0, 1e-6);
    let o = angles(t).to_rotation();
    let o_dot = (angles(t + h).to_rotation() - angles(t - h).to_rotation()) / (2.0 * h);
    let body = vee(&(o.transpose() * o_dot));
    let lab = vee(&(o_dot * o.transpose()));
    let from_3_5 = body_rate_from_euler(&angles(t), &rates);
    // ANCHOR_END: euler_convention
    writeln!(
        out,
        "\n(3.5) from the Euler rates:  [{:.6}, {:.6}, {:.6}]",
        from_3_5.x, from_3_5.y, from_3_5.z
    )?;
    writeln!(
        out,
        "      body rate (O^T dO/dt):  [{:.6}, {:.6}, {:.6}]",
        body.x, body.y, body.z
    )?;
    writeln!(
        out,
        "      lab rate (dO/dt O^T):   [{:.6}, {:.6}, {:.6}]  (not what (3.5) gives)",
        lab.x, lab.y, lab.z
    )?;
    let pole = EulerAngles::new(0.4, 0.0, 0.0);
    writeln!(
        out,
        "      at the pole theta = 0, (4.8) has no answer: euler_rates(..) = {:?}",
        euler_rates(&pole, w)
    )?;
    Ok(())
}

/// Why spintop integrates the orientation on SO(3): it stays a rotation.
fn orientation_on_so3(out: &mut dyn Write) -> io::Result<()> {
    writeln!(
        out,
        "\nAn asymmetric top, I = (1, 1.6, 0.9), d = (0.3, -0.2, 0.8), Omega0 = (0.1, 0.3, 0.5):"
    )?;
    writeln!(
        out,
        "{:>8} {:>14} {:>10} {:>14}",
        "method", "RHS evals", "steps", "|O^T O - I|"
    )?;
    let asym =
        GeneralTop::new(Vec3::new(1.0, 1.6, 0.9), Vec3::new(0.3, -0.2, 0.8)).expect("a rigid body");
    let initial = InitialState::new(Vec3::new(0.1, 0.3, 0.5), EulerAngles::new(0.0, 0.5, 0.0))
        .expect("finite");
    let mut theta = Vec::new();
    for (name, method) in [
        ("rk4", MethodChoice::Rk4),
        ("dopri5", MethodChoice::Dopri5),
        ("dop853", MethodChoice::Dop853),
    ] {
        let options = MethodOptions::new(1e-10, 0.05).expect("valid options");
        let mut sim = Simulation::new(Model::General(asym), method, options, initial, Some(1000.0))
            .expect("valid");
        let mut worst: f64 = 0.0;
        for i in 1..=400 {
            let s = sim.advance_to(2.5 * i as f64).expect("smooth");
            worst = worst.max(orthonormality_error(&s.rotation_matrix()));
            if name == "dop853" {
                theta.push((s.t, s.euler[1]));
            }
        }
        let stats = sim.stats();
        writeln!(
            out,
            "{name:>8} {:>14} {:>10} {:>14}",
            stats.rhs_evals,
            stats.steps,
            if worst < 1e-14 {
                "below 1e-14".to_string()
            } else {
                format!("{worst:.1e}")
            }
        )?;
    }
    let e_end = Simulation::new(
        Model::General(asym),
        MethodChoice::Auto,
        MethodOptions::default(),
        initial,
        None,
    )
    .and_then(|mut sim| Ok(sim.advance_to(1000.0)?.energy))
    .expect("smooth");
    let e0 = energy(&asym.inertia(), &initial.omega);
    writeln!(
        out,
        "  energy E = Omega.I Omega/2 falls from {e0:.4} to {e_end:.4e} by t = 1000"
    )?;
    writeln!(out)?;
    write!(
        out,
        "{}",
        chart(
            "theta(t) of the asymmetric top, DOP853 on SO(3)",
            &[Series::line("theta", theta)],
            (0.0, 1000.0),
            120,
            32
        )
    )?;
    Ok(())
}

#[allow(dead_code)]
fn main() -> io::Result<()> {
    run(&mut io::stdout().lock())
}
