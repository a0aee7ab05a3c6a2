//! The choice's rules on hand-made pilots: the noise split's bounded terms, the q fit's sign,
//! budget gains resolved in the bulk of pixels, and the radius for scattered light.

use super::*;
use crate::integrator::radius::AUTO_INDIRECT_SCALE;

/// An unresolved term counts as 0 only where the pilots bound it (`choose::BOUND_SHARE`): the
/// two cases that set the rule, height-fog's seed 6 and fog-room-laser's seed 2.
#[test]
fn an_unresolved_term_is_zero_only_where_the_pilots_bound_it() {
    let g = Gain::uniform;
    let height_fog = [
        g(3.116e-3, 1.9e-3),
        g(2.529e-2, 3.2e-3),
        g(2.925e-2, 6.4e-3),
    ];
    assert_eq!(choose::bounded(height_fog), [0.0, 2.529e-2, 2.925e-2]);
    let laser = [g(2.281e4, 4.3e4), g(1.050e5, 1.6e4), g(1.382e5, 3.5e4)];
    assert_eq!(choose::bounded(laser), [2.281e4, 1.050e5, 1.382e5]);
    let negative = [g(-7.5e3, 4.3e4), g(1.050e5, 1.6e4), g(1.382e5, 3.5e4)];
    assert_eq!(choose::bounded(negative)[0], 0.0);
}

/// The budgets' choice from pilots whose variance is `29.2 (0.25 + 0.75 / camera paths)` at
/// every q = 1, times `v_pilot / 29.2` for each medium at the pilots' q: three quarters camera
/// noise, so more camera paths pay up to a point the forward rays' cost sets.
fn choice_with_q_pilots(media: usize, v_pilot: f64) -> Choice {
    let base = PassConfig {
        q: vec![1.0; media],
        forward_rays: 50_000,
        camera_samples: 1,
        indirect_scale: 1.0,
    };
    let desc = IntegratorDesc::default();
    let mut t = Tuner::new(&desc, media, base, (64, 64)).expect("automatic");
    feed(&mut t, |c| {
        let drops = c.q.iter().filter(|q| **q < 1.0).count() as i32;
        29.2 * (v_pilot / 29.2).powi(drops) * (0.25 + 0.75 / c.camera_samples as f64)
    });
    t.choice().expect("chosen after the pilots").clone()
}

/// The q fit's variance at the chosen q scales the budgets' noise model, and only its sign can
/// change their choice (both models' variances multiply). With two media whose pilots each
/// drop from 29.2 to 10, the line `I + S1 q1 + S2 q2` through the pilots is -9.2 at q = 0.25
/// for both (I = -23.5): a negative noise model, whose "best" pass was the costliest (as
/// test_light_trace's spot fog, seed 7, had with one medium at q = 0.03: 16 camera paths x 50
/// 000 forward rays). The part not depending on q is floored at 0, so the budgets are those of
/// pilots whose line stays above 0: the pilots at q = 1 that split the noise are the same.
#[test]
fn a_q_fit_below_zero_does_not_turn_the_budgets_over() {
    let (below, above) = (choice_with_q_pilots(2, 10.0), choice_with_q_pilots(2, 25.0));
    let says = |c: &Choice, s: &str| c.report.iter().any(|l| l.contains(s));
    assert!(says(&below, "I = -"), "below 0: {:?}", below.report);
    assert!(!says(&above, "I = -"), "above 0: {:?}", above.report);
    let budgets = |c: &Choice| (c.config.camera_samples, c.config.forward_rays);
    assert_eq!(budgets(&below), budgets(&above), "{:?}", below.report);
    assert!(
        budgets(&above) != (MAX_CAMERA_SAMPLES, 50_000),
        "the test's optimum is inside the search: {:?}",
        above.report
    );
    assert!(
        below
            .report
            .iter()
            .filter(|l| l.starts_with("budgets: camera paths"))
            .all(|l| !l.contains("+ -") && !l.contains("= -")),
        "no negative term in the noise model: {:?}",
        below.report
    );
}

/// A line through the pilots that falls below 0 is no variance `S q + I` with I >= 0: its
/// optimum, q -> 0, is an extrapolation past what the pilots measured, and the lowest q they
/// measured stays (spot fog's seed 7: 29.2 at q = 1, 2.02 at 0.25). A line above 0 still
/// chooses by the time-optimal rule: here, with no sphere cost in the synthetic work, `Q_MIN`.
#[test]
fn a_q_fit_below_zero_keeps_the_lowest_q_measured() {
    let q = |v_pilot| choice_with_q_pilots(1, v_pilot).config.q[0];
    assert_eq!(q(2.0), Q_PILOT);
    assert_eq!(q(20.0), Q_MIN);
}

/// Per-pixel pilot estimates `d = (x1 - x2)^2 / 2` of `pixels` pixels of variance `bulk`, and
/// of `tail` more whose variance is `bright`: two passes per pixel, normal noise.
fn pilot_d(
    rng: &mut Pcg64Mcg,
    (pixels, bulk): (usize, f64),
    (tail, bright): (usize, f64),
) -> Vec<f64> {
    let normal = |rng: &mut Pcg64Mcg| {
        // Box-Muller: one standard normal number.
        let (u, v): (f64, f64) = (rng.random::<f64>().max(1e-300), rng.random());
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    };
    (0..pixels + tail)
        .map(|i| {
            let var = if i < pixels { bulk } else { bright };
            let (a, b) = (normal(rng) * var.sqrt(), normal(rng) * var.sqrt());
            (a - b) * (a - b) / 2.0
        })
        .collect()
}

/// A gain resolved in the bulk (`gain::TAIL_SHARE`) counts where a few bright pixels hide it
/// over every pixel (chromatic-fog's pilots), and only with the sign the whole image gives it;
/// a bulk that gains nothing resolves nothing, whatever the tail does.
#[test]
fn a_gain_hidden_by_a_few_bright_pixels_is_resolved_by_the_bulk() {
    let mut rng = Pcg64Mcg::seed_from_u64(30);
    let (pixels, tail) = (8000, 4);
    // The Samples pilot's case: 4x the camera paths, a quarter of the variance everywhere.
    let before = pilot_d(&mut rng, (pixels, 1.0), (tail, 2.0e4));
    let after = pilot_d(&mut rng, (pixels, 0.25), (tail, 0.5e4));
    let g = Gain::paired(&before, &after);
    assert!(
        g.gain < Z_SIGNIFICANT * g.se,
        "hidden over every pixel: {g:?}"
    );
    assert!(g.bulk.0 > 10.0 * g.bulk.1, "resolved in the bulk: {g:?}");
    assert_eq!(g.resolved_or_bulk(), Some(g.gain));
    // The bulk unchanged: nothing to act on, and the tail's difference is noise. The bulk's
    // test then resolves a gain at the one-sided 2.3 % of a z-test, halved again by the sign
    // over every pixel: at most 2 of 40 seeds (expected 0.5; 3 or more has probability 0.01).
    let resolved = (0..40)
        .filter(|seed| {
            let mut rng = Pcg64Mcg::seed_from_u64(100 + seed);
            let before = pilot_d(&mut rng, (pixels, 1.0), (tail, 2.0e4));
            let after = pilot_d(&mut rng, (pixels, 1.0), (tail, 2.0e4));
            Gain::paired(&before, &after).resolved_or_bulk().is_some()
        })
        .count();
    assert!(resolved <= 2, "{resolved} of 40 null bulks resolved");
    // A bulk gain against a loss over every pixel: the sign is the whole image's.
    let before = pilot_d(&mut rng, (pixels, 1.0), (tail, 1.0e4));
    let after = pilot_d(&mut rng, (pixels, 0.5), (tail, 3.0e4));
    let g = Gain::paired(&before, &after);
    assert!(g.gain < 0.0 && g.bulk.0 > Z_SIGNIFICANT * g.bulk.1, "{g:?}");
    assert_eq!(g.resolved_or_bulk(), None);
    // With no tail the bulk is every pixel but its largest 0.2 %: the same verdict.
    let before = pilot_d(&mut rng, (pixels, 1.0), (0, 0.0));
    let after = pilot_d(&mut rng, (pixels, 0.8), (0, 0.0));
    let g = Gain::paired(&before, &after);
    assert!(
        g.resolved_or_bulk().is_some() && g.gain > Z_SIGNIFICANT * g.se,
        "{g:?}"
    );
}

/// The Radius pilot's choice (`choose_radius`), on pilots whose variance is `29.2 (0.25 + 0.75
/// / camera paths)` times `k` at the larger radius for scattered light, and whose work does not
/// depend on the radius: the criterion's ratio is then about k^2 (per pixel and per block).
fn radius_choice(desc: IntegratorDesc, k: f64) -> Choice {
    let base = PassConfig {
        q: vec![1.0],
        forward_rays: 50_000,
        camera_samples: 1,
        indirect_scale: 1.0,
    };
    let mut t = Tuner::new(&desc, 1, base, (64, 64)).expect("automatic");
    feed(&mut t, |c| {
        let radius = if c.indirect_scale == 1.0 { 1.0 } else { k };
        29.2 * radius * (0.25 + 0.75 / c.camera_samples as f64)
    });
    t.choice().expect("chosen after the pilots").clone()
}

/// A larger radius is taken only when its pilot's gain is resolved and large (ratio about 0.25
/// against `RADIUS_GAIN_NEEDED` = 0.5): a ratio of about 0.64, or a larger variance, keeps the
/// radius; a scene that sets either radius has no Radius pilot, and neither has one that
/// does not ask for it (`radius_indirect = "auto"` is opt-in).
#[test]
fn the_radius_for_scattered_light_doubles_only_on_a_large_resolved_gain() {
    let scale = |c: &Choice| c.config.indirect_scale;
    let opt_in = || IntegratorDesc {
        radius_indirect: Some(Setting::Auto),
        ..IntegratorDesc::default()
    };
    let large = radius_choice(opt_in(), 0.5);
    assert_eq!(scale(&large), AUTO_INDIRECT_SCALE, "{:?}", large.report);
    assert!(settings_of(&large.config).ends_with("radius_indirect = 2 x radius"));
    let small = radius_choice(opt_in(), 0.8);
    assert_eq!(scale(&small), 1.0, "{:?}", small.report);
    assert_eq!(scale(&radius_choice(opt_in(), 1.5)), 1.0);
    let by_default = radius_choice(IntegratorDesc::default(), 0.5);
    assert_eq!(scale(&by_default), 1.0);
    assert!(
        !by_default.report.iter().any(|l| l.contains("Radius")),
        "{:?}",
        by_default.report
    );
    let set = IntegratorDesc {
        radius: Setting::Value(0.01),
        ..opt_in()
    };
    let fixed = radius_choice(set, 0.5);
    assert_eq!(scale(&fixed), 1.0);
    assert!(
        !fixed.report.iter().any(|l| l.contains("Radius")),
        "{:?}",
        fixed.report
    );
    let second = IntegratorDesc {
        radius_indirect: Some(Setting::Value(0.02)),
        ..IntegratorDesc::default()
    };
    assert_eq!(scale(&radius_choice(second, 0.5)), 1.0);
}
