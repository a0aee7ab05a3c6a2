//! The radius for scattered light: the automatic radius, or `AUTO_INDIRECT_SCALE` times it,
//! from the first two pilot pairs (Narrow, at the radius, and Radius, at the larger one); every
//! later pilot then samples at the radius they chose, so that q and the budgets are chosen for
//! it (chosen at the smaller radius and rendered at the larger, fog-cube's budgets were
//! 198 896 forward rays x 2 camera paths where its pilots at the larger radius choose about
//! 41 000 x 1, and its binned error at 10 s was 1.12x the smaller radius's).
//!
//! Light that has scattered at least once is smooth where the light is broad (a parallel light
//! in fog: its multiply scattered light varies over the fog's size) and sharp where it is narrow
//! (around a spot's beam): a larger radius gathers more of it per forward ray where it is
//! smooth, and blurs it where it is not, at more gather hits either way. The pilots measure the
//! noise and the cost, not the blur, so the larger radius is only ever the one of 3 pixel
//! footprints (`AUTO_INDIRECT_SCALE`), and only where the scene asks for it
//! (`radius_indirect = "auto"`): its blur is about 0.1 % of fog-cube's mean, but 2.2 % of
//! smoke-plume's and 0.3 % of height-fog's (4x4-binned), the floor of their one-minute renders,
//! which the pilots' noise cannot show (docs/performance.md, "The radius for scattered light
//! chosen by the pilots: a blur they do not see").

use super::{Gain, Role, Tuner};

/// Pilot passes (pairs) that choose the radius: Narrow and Radius.
pub const PASSES: u64 = 2;

/// The Radius pilot's `V_pixel V_block C^2` (the budgets' criterion) over Narrow's that the
/// choice needs. The two sample at the base budgets, where the gathered light's noise is a
/// larger share of the variance than at the chosen budgets, so they overrate the radius's gain:
/// on fog-cube their ratio is 0.15-0.23 (seeds 1-5), while at 10 s of wall time the larger
/// radius's variance x time is about 0.6x per pixel and 0.8x binned. On the eight protocol
/// scenes (seeds 1-5, docs/performance.md) the ratio is 0.14-0.45 on the three parallel-light
/// fogs and smoke-plume, where the larger radius renders with less noise at equal time, and
/// mostly 0.9-22 on fog-bank, valley-fog, fog-room-laser and chromatic-fog's narrow spot, where
/// it does not or gains little.
pub const RADIUS_GAIN_NEEDED: f64 = 0.5;

impl Tuner {
    /// Chooses the radius for scattered light from the Narrow and Radius pilots: the larger one
    /// when its per-pixel variance is resolved below Narrow's (the paired gain, as the budgets'
    /// gains) and the criterion's ratio is under `RADIUS_GAIN_NEEDED`. Then every later pilot
    /// pass, and every role's configuration but Narrow's, samples at the radius chosen.
    pub(super) fn choose_radius(&mut self) {
        let (Some((wide, r)), Some((_, n))) =
            (self.measure(Role::Radius), self.measure(Role::Narrow))
        else {
            return;
        };
        let scale = wide.indirect_scale;
        let blocks = (
            self.block_variance_of(Role::Narrow),
            self.block_variance_of(Role::Radius),
        );
        let (Some(n_block), Some(r_block)) = blocks else {
            return;
        };
        let (n_cost, r_cost) = (n.work.cost(), r.work.cost());
        let ratio = if n.variance > 0.0 && n_block > 0.0 && n_cost > 0.0 {
            (r.variance / n.variance) * (r_block / n_block) * (r_cost / n_cost).powi(2)
        } else {
            f64::INFINITY
        };
        let resolved = self
            .gain_between(&self.shares, Role::Narrow, Role::Radius)
            .and_then(|g| g.resolved())
            .is_some();
        let take = resolved && ratio < RADIUS_GAIN_NEEDED;
        if take {
            for p in self.passes.iter_mut().skip(PASSES as usize) {
                p.config.indirect_scale = scale;
            }
            for (role, c) in self.pilots.iter_mut() {
                if *role != Role::Narrow {
                    c.indirect_scale = scale;
                }
            }
        }
        self.radius_report = Some(format!(
            "radius for scattered light: x {scale} the radius's V_pixel V_block C^2 x {ratio:.3} \
             (variance gain {}resolved; taken below {RADIUS_GAIN_NEEDED}): radius_indirect = {} x \
             radius, the later pilots' and the passes'",
            if resolved { "" } else { "not " },
            if take { scale } else { 1.0 }
        ));
    }

    /// Pilot `role`'s block variance per pass.
    pub(super) fn block_variance_of(&self, role: Role) -> Option<f64> {
        let i = self.pilots.iter().position(|(p, _)| *p == role)?;
        Some(self.block_shares.get(i)?.iter().sum())
    }

    /// How much pilot `role` lowered the variance below pilot `before`'s, pixel by pixel.
    pub(super) fn gain_between(
        &self,
        shares: &[Vec<f64>],
        before: Role,
        role: Role,
    ) -> Option<Gain> {
        let (base, other) = (
            self.shares_of(shares, before)?,
            self.shares_of(shares, role)?,
        );
        // A pilot pair whose two passes agree in every pixel (both saw no light: a rare light
        // missed twice) measured nothing, not a variance of zero.
        if other.iter().all(|d| *d == 0.0) {
            return Some(Gain::uniform(0.0, 0.0));
        }
        Some(Gain::paired(base, other))
    }
}
