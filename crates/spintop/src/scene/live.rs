//! What the live view opens for a scene: the model, Ω₀, the method and the
//! line it opens with. The view runs in τ units (κ = 1 units for a general
//! top), with the lab z axis along L₀.

use super::{Body, Scene, catalogue};
use crate::math::Real;
use crate::sim::{MethodChoice, MethodOptions, Model};

/// A top scene as the live view opens it.
#[derive(Clone, Debug, PartialEq)]
pub struct LiveScene {
    /// The scene's model: a symmetric one opens the two symmetric columns, a
    /// general one the three general columns.
    pub model: Model,
    /// Ω₀, body frame.
    pub omega0: [Real; 3],
    /// The method of the columns that take one (the full ALE's physical
    /// solution has its own).
    pub method: MethodChoice,
    /// O(0) as z-x-z Euler angles where the scene gives them (or leaves the
    /// default 0, 0, 0), as `spintop run` starts it; `None` for the paper's
    /// frame (lab z along L₀), the view's own start.
    pub euler0: Option<[Real; 3]>,
    /// The line the view opens with.
    pub note: String,
}

/// The live view's start for a top scene.
///
/// A truncated or reduced scene opens the symmetric layout, the truncated
/// and reduced models side by side, with its I₃/I₁, Ω₀ and method; a full
/// scene opens the full ALE's physical solution beside its forward run.
/// An asymmetric (general) scene opens the general layout: the truncated ALE
/// (3.3) and its neighbours with their moments and dipole, integrated by the
/// scene's method (for `auto`, the integrator `auto` takes at the view's
/// rtol, since nothing is closed: [`crate::sim::auto_integrator`]). Scenes of
/// other kinds are refused, in one line that says what to run instead.
pub fn live_scene(scene: &Scene) -> Result<LiveScene, String> {
    let Body::Top(top) = &scene.body else {
        // A catalogue scene is run by its name, which works from any folder;
        // its repository path would not.
        let runnable = match catalogue::find(&scene.name) {
            Some(entry) if entry.path() == scene.file => scene.name.clone(),
            _ => scene.file.clone(),
        };
        return Err(format!(
            "{}: the live view opens top scenes, and this one is kind = \"{}\"; use `spintop run {runnable}`",
            scene.file,
            scene.kind().name(),
        ));
    };
    // The view names the method its lighter columns run (the full ALE's
    // column always shows its physical solution): what `auto` runs on the
    // scene's lightest model at the view's tolerance, where that is a
    // choice of its own (an integrator for a general top: the Taylor method
    // at the default rtol 1e-10, by the measured crossover), else the closed
    // forms, for `auto`, `exact` and `forward` (which is not a view).
    let method = match top.method {
        MethodChoice::Auto | MethodChoice::Exact | MethodChoice::Forward => top.model.tiers()[0]
            .method(MethodChoice::Auto, &MethodOptions::default())
            .ok()
            .and_then(|m| m.choice())
            .unwrap_or(MethodChoice::Exact),
        other => other,
    };
    let mut note = format!("scene {}", scene.name);
    match top.model {
        Model::General(_) | Model::GeneralReduced(_) | Model::GeneralFull(_) => {
            if let Some(g) = &top.general_units {
                note.push_str(&format!(
                    ": a real particle, τ_f = {:.2e} s, far too slow to watch in these units; `spintop run {}` gives its secular drift",
                    g.fast_time_seconds(),
                    scene.name
                ));
            } else {
                note.push_str(&format!(
                    ": a general top under (3.3), the reduced ALE and the physical solution of (3.4) side by side, the first two integrated by {}; time in u, the unit where κ = 1",
                    method.title()
                ));
            }
        }
        Model::Truncated(_) | Model::Reduced(_) | Model::Full(_) => {
            if let Some(u) = &top.units {
                note.push_str(&format!(
                    ": a real particle, τ = {:.2e} s, far too slow to watch in τ units; `spintop run {}` gives its times",
                    u.tau_seconds(),
                    scene.name
                ));
            } else if matches!(top.model, Model::Full(_)) {
                note.push_str(": the full ALE (3.4), its physical solution beside the same equation integrated forward, which runs away");
            } else {
                note.push_str(&format!(": {}", scene.summary()));
            }
        }
    }
    Ok(LiveScene {
        model: top.model,
        omega0: top.initial.omega.into(),
        method,
        euler0: (top.frame == super::top::Frame::Euler).then_some(top.euler0),
        note,
    })
}
