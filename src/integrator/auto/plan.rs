//! Which pilot passes a tuner renders, and which of its measured configurations (`Role`)
//! each gives.
//!
//! Every role is a configuration whose variance and cost the choice needs. The budget roles
//! (Base, Rays, Samples, Both) are nested in one pass (`integrator::nest`): the pass of the
//! most camera paths and forward rays, whose first paths and rays are the others' passes. A
//! medium's q pilot changes the camera paths' volumes, not their number, so it stays a pass of
//! its own, as does the Radius pilot (its gather structure's bounds are larger).

use super::{BUDGET_FACTOR, PILOT_STRIDE, PassConfig, Role, Tuner};
use crate::integrator::nest::{Nest, Variant};
use crate::integrator::radius::AUTO_INDIRECT_SCALE;

/// One pilot configuration rendered (twice: `REPEATS`), and the roles it measures.
#[derive(Clone, Debug)]
pub struct PilotPass {
    pub config: PassConfig,
    /// Indices into the tuner's roles, each with the nested estimate that measures it (None:
    /// the pass itself).
    pub roles: Vec<(usize, Option<usize>)>,
    /// The estimates nested in the pass (None: it measures one role).
    pub nest: Option<Nest>,
}

/// The roles a tuner measures, in the order its reports give them, and the passes that
/// measure them. `pilot` is the Base configuration, `media` the scene's media, `auto_q` whether
/// their q is automatic, `auto_radius` whether the radius for scattered light is, and `q_pilot`
/// the q of a medium's pilot.
pub fn plan(
    pilot: &PassConfig,
    media: usize,
    (auto_q, auto_radius): (bool, bool),
    (auto_rays, auto_samples): (bool, bool),
    q_pilot: f32,
) -> (Vec<(Role, PassConfig)>, Vec<PilotPass>) {
    let mut roles = vec![(Role::Base, pilot.clone())];
    let mut passes = Vec::new();
    if auto_q {
        for m in 0..media {
            let mut c = pilot.clone();
            c.q[m] = q_pilot;
            passes.push(PilotPass {
                config: c.clone(),
                roles: vec![(roles.len(), None)],
                nest: None,
            });
            roles.push((Role::Medium(m), c));
        }
    }
    let budget = nested_budgets(pilot, &mut roles, (auto_rays, auto_samples));
    // The budget pass first, or Base alone (then with q alone automatic the pilots are film
    // passes, Base's pair first as it always was).
    passes.insert(
        0,
        budget.unwrap_or_else(|| PilotPass {
            config: pilot.clone(),
            roles: vec![(0, None)],
            nest: None,
        }),
    );
    if auto_radius {
        // First, so that every later pilot samples at the radius these two choose
        // (`Tuner::choose_radius`).
        let mut wide = pilot.clone();
        wide.indirect_scale = AUTO_INDIRECT_SCALE;
        for (i, (role, c)) in [(Role::Narrow, pilot.clone()), (Role::Radius, wide)]
            .into_iter()
            .enumerate()
        {
            passes.insert(
                i,
                PilotPass {
                    config: c.clone(),
                    roles: vec![(roles.len(), None)],
                    nest: None,
                },
            );
            roles.push((role, c));
        }
    }
    (roles, passes)
}

/// The pass that nests the budget roles (Base, and Rays, Samples and Both as the automatic
/// budgets have them), adding them to `roles`; None without automatic budgets.
fn nested_budgets(
    pilot: &PassConfig,
    roles: &mut Vec<(Role, PassConfig)>,
    (auto_rays, auto_samples): (bool, bool),
) -> Option<PilotPass> {
    let k = BUDGET_FACTOR;
    let scaled = |rays: bool, samples: bool| {
        let mut c = pilot.clone();
        if rays {
            c.forward_rays *= k;
        }
        if samples {
            c.camera_samples *= k as u32;
        }
        c
    };
    // Each budget role with the budgets it multiplies.
    let budget: Vec<(Role, bool, bool)> = [
        (Role::Rays, true, false),
        (Role::Samples, false, true),
        (Role::Both, true, true),
    ]
    .into_iter()
    .filter(|(_, rays, samples)| (!rays || auto_rays) && (!samples || auto_samples))
    .collect();
    if budget.is_empty() {
        return None;
    }
    // The nest is the pass of every automatic budget times k; Base keeps the first paths and
    // rays of it, the others the first of what they do not multiply.
    let mut variants = vec![Variant {
        sub_paths: auto_samples,
        sub_rays: auto_rays,
    }];
    let mut nested = vec![(0, Some(0))];
    for (role, rays, samples) in budget {
        let index = roles.len();
        roles.push((role, scaled(rays, samples)));
        let v = Variant {
            sub_paths: auto_samples && !samples,
            sub_rays: auto_rays && !rays,
        };
        if v.sub_paths || v.sub_rays {
            nested.push((index, Some(variants.len())));
            variants.push(v);
        } else {
            nested.push((index, None));
        }
    }
    let factor = |on: bool| if on { k as f32 } else { 1.0 };
    Some(PilotPass {
        config: scaled(auto_rays, auto_samples),
        roles: nested,
        nest: Some(Nest {
            paths: pilot.camera_samples,
            rays: pilot.forward_rays,
            path_factor: factor(auto_samples),
            ray_factor: factor(auto_rays),
            variants,
        }),
    })
}

impl Tuner {
    /// What the pilot passes are to the render, in words for the report: a short render's user
    /// must not read "pilot passes 0..8" of a 2-pass render as passes of its film.
    pub(super) fn pilots_said(&self) -> String {
        let n = self.pilot_passes();
        if self.pilots_join_film() {
            format!(
                "{n} pilot passes, the film's passes 0..{n} (kept in the image; a render of \
                 fewer than {n} passes has only pilots, at their own q, and makes no choice)"
            )
        } else {
            format!(
                "{n} pilot passes rendered before the film's first pass and NOT in the film \
                 (every process of the render traces them first, however few passes it asks \
                 for: a render of N passes traces N + {n}; each pilot traces camera paths in \
                 one pixel of {k} and, with automatic forward rays, {k} times fewer of them{nested})",
                k = PILOT_STRIDE * PILOT_STRIDE,
                nested = if self.passes.iter().any(|p| p.nest.is_some()) {
                    format!(
                        "; the budget pilots are estimates nested in one pass of {BUDGET_FACTOR} \
                         times their camera paths or rays, from its first paths and rays"
                    )
                } else {
                    String::new()
                }
            )
        }
    }
}
