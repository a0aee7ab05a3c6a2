//! The tuner's choice from synthetic pilot passes: per-pixel totals drawn with a known
//! variance per configuration, so that the choice the models must make is known.

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use super::*;
use crate::integrator::setting::Setting;

const PIXELS: usize = 4096;

/// A tuner of `desc` for one medium and a 64 x 64 image, from the default base (q 1, 50 000
/// forward rays, 1 camera path).
fn tuner(desc: IntegratorDesc) -> Tuner {
    let base = PassConfig {
        q: vec![1.0],
        forward_rays: 50_000,
        camera_samples: 1,
        indirect_scale: 1.0,
    };
    Tuner::new(&desc, 1, base, (64, 64)).expect("something is automatic")
}

/// A tuner with automatic budgets only (q fixed at 1).
fn budget_tuner() -> Tuner {
    tuner(IntegratorDesc {
        q: Setting::Value(1.0),
        ..IntegratorDesc::default()
    })
}

/// A tuner with q alone automatic (50 000 forward rays and 1 camera path fixed).
fn q_tuner() -> Tuner {
    tuner(IntegratorDesc {
        forward_rays: Setting::Value(50_000),
        camera_samples: Setting::Value(1),
        ..IntegratorDesc::default()
    })
}

/// Uniform noise of standard deviation `sd` (variance sd^2).
fn uniform(rng: &mut Pcg64Mcg, sd: f64) -> f64 {
    sd * 3f64.sqrt() * (2.0 * rng.random::<f64>() - 1.0)
}

/// Feeds every pilot pass of `t`, an image of `pixels` pixels: the totals `totals(pass,
/// config)`, and work that grows with the configuration's rays and camera paths, counted, like
/// the renderer's, on the pixels the pass traces (`pixel_stride`).
/// A pass's nested estimates are fed as the estimates of their own configurations
/// (`Tuner::measured_configs`).
fn feed_totals(t: &mut Tuner, pixels: usize, mut totals: impl FnMut(u64, &PassConfig) -> Vec<f64>) {
    for pass in 0..t.pilot_passes() {
        let traced = (pixels / (t.pixel_stride(pass) as usize).pow(2)) as u64;
        let mut measured = t.measured_configs(pass).into_iter().map(|c| {
            let work = Work {
                paths: traced * c.camera_samples as u64,
                volumes: traced * c.camera_samples as u64,
                rays: c.forward_rays,
                hits: c.forward_rays * c.camera_samples as u64 * traced / pixels as u64,
            };
            (totals(pass, &c), work)
        });
        let (totals, work) = measured.next().expect("a pilot pass");
        let result = PilotResult {
            totals,
            work,
            variants: measured.collect(),
        };
        t.record(pass, result);
    }
}

/// Feeds every pilot pass: pixel values of mean 1 and variance `variance(config)` over the
/// image (64 x 64 pixels).
fn feed(t: &mut Tuner, variance: impl Fn(&PassConfig) -> f64) {
    let mut rng = Pcg64Mcg::seed_from_u64(7);
    feed_totals(t, PIXELS, |_, c| {
        let sd = (variance(c) / PIXELS as f64).sqrt();
        (0..PIXELS).map(|_| 1.0 + uniform(&mut rng, sd)).collect()
    });
}

#[test]
fn budgets_that_buy_nothing_fall_to_the_cheapest_passes() {
    let mut t = budget_tuner();
    // The same variance whatever the budgets: neither pilot can lower it.
    feed(&mut t, |_| 1.0);
    let choice = t.choice().expect("chosen after the pilots");
    assert_eq!(choice.config.camera_samples, 1, "{:?}", choice.report);
    assert_eq!(
        choice.config.forward_rays, RAYS_RANGE.0,
        "{:?}",
        choice.report
    );
}

#[test]
fn camera_noise_alone_buys_camera_paths() {
    let mut t = budget_tuner();
    // Variance 1 / camera paths: camera paths buy a measured gain and are cheap against the
    // forward rays' work, so the search adds them.
    feed(&mut t, |c| 1.0 / c.camera_samples as f64);
    let choice = t.choice().expect("chosen after the pilots");
    let c = &choice.config;
    assert!(c.camera_samples > 1, "{:?}", choice.report);
    // The search keeps rays within BUDGET_FACTOR^2 of the base.
    assert_eq!(
        c.forward_rays, 50_000,
        "rays not measured by a gain keep the base"
    );
}

#[test]
fn a_pilot_that_saw_no_light_is_no_evidence() {
    let mut t = budget_tuner();
    // With more camera paths both pilot passes agree in every pixel (as when both miss a rare
    // light): that is no measured gain, so the budgets fall to the cheapest pass, not to the
    // most camera paths.
    feed(&mut t, |c| if c.camera_samples > 1 { 0.0 } else { 1.0 });
    let choice = t.choice().expect("chosen after the pilots");
    assert_eq!(choice.config.camera_samples, 1, "{:?}", choice.report);
}

/// Issue 31: `-v` said "chosen from pilot passes 0..8" for a 2-pass render whose first pass
/// took 8 s. The report says what the pilots are to the render.
#[test]
fn the_report_says_what_a_short_render_does_with_its_pilots() {
    let mut t = budget_tuner();
    feed(&mut t, |_| 1.0);
    let first = &t.choice().expect("chosen").report[0];
    assert!(
        first.contains("2 pilot passes rendered before the film's first pass and NOT in the film")
            && first.contains("a render of N passes traces N + 2")
            && first.contains("nested"),
        "{first}"
    );
    let mut t = q_tuner();
    feed(&mut t, |_| 1.0);
    let first = &t.choice().expect("chosen").report[0];
    assert!(
        first.contains("4 pilot passes, the film's passes 0..4")
            && first.contains("fewer than 4 passes has only pilots"),
        "{first}"
    );
}

/// Pilots outside the film sample a lattice of a quarter of the pixels with a quarter of the
/// base's forward rays, and report the whole image's variance and cost: the Base pilot's
/// variance per pass (10.0 over the image, estimated from 1024 lattice pixels: standard error
/// about 4.4 %) is read back within 20 % (4.5 standard errors), its cost as the whole image's.
#[test]
fn pilots_outside_the_film_sample_a_lattice_with_fewer_rays() {
    let mut t = budget_tuner();
    assert!(!t.pilots_join_film());
    let base = t.role_config(Role::Base).expect("the base pilot").clone();
    assert_eq!(base.forward_rays, 50_000 / 4);
    // One pass nests the four budget pilots: the largest (k s, k n). (No Narrow and Radius
    // pilots: the radius for scattered light is not asked for.)
    assert_eq!(t.pilot_passes(), REPEATS);
    let nest = t.config(0).expect("the nested pilot");
    assert_eq!((nest.forward_rays, nest.camera_samples), (50_000, 4));
    for pass in 0..t.pilot_passes() {
        assert_eq!(t.pixel_stride(pass), PILOT_STRIDE, "pilot pass {pass}");
    }
    assert_eq!(
        t.pixel_stride(t.pilot_passes()),
        1,
        "film passes trace every pixel"
    );
    feed(&mut t, |_| 10.0);
    let (_, m) = t.measure(Role::Base).expect("measured");
    assert!((m.variance / 10.0 - 1.0).abs() < 0.2, "{m:?}");
    let whole = Work {
        paths: PIXELS as u64,
        volumes: PIXELS as u64,
        rays: 12_500,
        hits: 12_500,
    };
    assert!((m.work.cost() / whole.cost() - 1.0).abs() < 1e-6, "{m:?}");
    // Budgets that buy nothing fall back from the scene's budgets, not the pilots'.
    let choice = t.choice().expect("chosen");
    assert_eq!(
        choice.config.forward_rays, RAYS_RANGE.0,
        "{:?}",
        choice.report
    );
}

/// With q alone automatic the pilots are film passes: every pixel, the scene's budgets.
#[test]
fn film_pilots_trace_every_pixel_at_the_scene_budgets() {
    let t = q_tuner();
    assert!(t.pilots_join_film());
    for pass in 0..t.pilot_passes() {
        assert_eq!(t.pixel_stride(pass), 1);
        assert_eq!(t.config(pass).map(|c| c.forward_rays), Some(50_000));
    }
}

/// Pilots outside the film draw the first pair's random numbers in every configuration; the
/// film's passes and film pilots draw their own.
#[test]
fn pilots_outside_the_film_share_their_random_numbers() {
    // The nested budget pilots and the medium's; film passes start after a pair per role
    // (Base, Rays, Samples, Both, the medium's).
    let t = tuner(IntegratorDesc::default());
    assert_eq!((t.pilot_passes(), t.film_offset()), (4, 10));
    // With the radius for scattered light asked for, the Narrow and Radius pilots first: two
    // more pairs.
    let t = tuner(IntegratorDesc {
        radius_indirect: Some(Setting::Auto),
        ..IntegratorDesc::default()
    });
    let p = t.pilot_passes();
    assert_eq!(p, 8);
    assert_eq!(t.film_offset(), 14);
    for pass in 0..p {
        assert_eq!(t.random_pass(pass), pass % REPEATS, "pilot pass {pass}");
    }
    for pass in t.film_offset()..t.film_offset() + 4 {
        assert_eq!(t.random_pass(pass), pass, "film pass {pass}");
    }
    let t = q_tuner();
    for pass in 0..t.pilot_passes() + 2 {
        assert_eq!(t.random_pass(pass), pass, "film pilot {pass}");
    }
}

/// A tuner with q and the budgets automatic for a 256 x 256 image (the pixel count sets how well
/// a pilot knows its variance). The radius is set, so that no Radius pilot runs: these tests
/// are about the q and budget pilots, and their own noise is one stream over the pilot passes.
fn auto_tuner_256() -> Tuner {
    let base = PassConfig {
        q: vec![1.0],
        forward_rays: 50_000,
        camera_samples: 1,
        indirect_scale: 1.0,
    };
    let desc = IntegratorDesc {
        radius: Setting::Value(0.01),
        ..IntegratorDesc::default()
    };
    Tuner::new(&desc, 1, base, (256, 256)).expect("automatic")
}

/// Feeds every pilot pass of `t` (a 256 x 256 image): per pixel a component of variance `shared`
/// (per pass, over the image) drawn from the pass's random numbers (`random_pass`, or the pass
/// itself when `paired` is false: independent pilots), as the forward rays' noise is, plus one
/// of variance `own(config)` that only the pilot's configuration sets.
fn feed_shared(t: &mut Tuner, shared: f64, own: impl Fn(&PassConfig) -> f64, paired: bool) {
    const N: usize = 256 * 256;
    let mut own_rng = Pcg64Mcg::seed_from_u64(11);
    let keys: Vec<u64> = (0..t.pilot_passes())
        .map(|pass| if paired { t.random_pass(pass) } else { pass })
        .collect();
    feed_totals(t, N, |pass, c| {
        let mut shared_rng = Pcg64Mcg::seed_from_u64(1000 + keys[pass as usize]);
        let (sd_shared, sd_own) = ((shared / N as f64).sqrt(), (own(c) / N as f64).sqrt());
        (0..N)
            .map(|_| 1.0 + uniform(&mut shared_rng, sd_shared) + uniform(&mut own_rng, sd_own))
            .collect()
    });
}

/// q = 0.25 lowers the variance from 404 to 401 per pass, where 400 of it is noise that every
/// configuration shares (the forward rays' at the pilots' budgets). Compared pixel by pixel
/// over the 16 384 lattice pixels, the gain of 3 has a standard error of about 0.7 (z about
/// 4.3: the noise left is the shared part times the configuration's own, `Gain::paired`), and
/// q falls. The same pilots drawn independently compare two variances each known to about
/// 1.1 %: a standard error of about 5 (z under 1), which no gate can act on. That is what
/// kept q = 1 on 2 of 16 of height-fog's seeds before the pilots shared their numbers.
#[test]
fn shared_pilot_noise_cancels_and_resolves_q_gain() {
    let own = |c: &PassConfig| if c.q[0] < 1.0 { 1.0 } else { 4.0 };
    let mut t = auto_tuner_256();
    feed_shared(&mut t, 400.0, own, true);
    let paired = t.gain(Role::Medium(0)).expect("measured");
    assert!(paired.gain > Z_SIGNIFICANT * paired.se, "{paired:?}");
    assert!((paired.gain / 3.0 - 1.0).abs() < 0.7, "{paired:?}");
    let choice = t.choice().expect("chosen");
    assert!(choice.config.q[0] < 1.0, "{:?}", choice.report);

    let mut t = auto_tuner_256();
    feed_shared(&mut t, 400.0, own, false);
    let apart = t.gain(Role::Medium(0)).expect("measured");
    assert!(apart.se > 4.0 * paired.se, "{apart:?} against {paired:?}");
}

/// No gain, the same shared noise: the paired comparison must not invent one (the gate's
/// false positive).
#[test]
fn shared_pilot_noise_invents_no_gain() {
    let mut t = auto_tuner_256();
    feed_shared(&mut t, 400.0, |_| 4.0, true);
    let g = t.gain(Role::Medium(0)).expect("measured");
    assert!(g.gain.abs() < Z_SIGNIFICANT * g.se, "{g:?}");
    let choice = t.choice().expect("chosen");
    assert_eq!(choice.config.q[0], 1.0, "{:?}", choice.report);
}

/// Feeds every pilot pass of `t` (a 256 x 256 image) values with brume's noise structure at
/// per-pixel variances `a / s + b / g + c / (s g)`, with s the pilot's camera paths and g its
/// forward rays in units of the Base pilot's: the camera paths' noise `a` is each pixel's own;
/// the forward rays' `b` is a line (one value per row, as a forward segment's deposits are),
/// the strongest noise and the one a pilot's whole variance is least sure of; their meeting
/// `c` is each pixel's own. Every component is drawn from the pass's random numbers
/// (`random_pass`), camera path by camera path and ray group by ray group, so that a pilot with
/// 4 times the rays shares its first group with the Base pilot, as brume's pilots do.
fn feed_structured(t: &mut Tuner, (a, b, c): (f64, f64, f64)) {
    const W: usize = 256;
    let keys: Vec<u64> = (0..t.pilot_passes()).map(|p| t.random_pass(p)).collect();
    let base = t.role_config(Role::Base).expect("a pilot").clone();
    let draw = |key: u64, part: u64, index: u64, len: usize, v: f64| -> Vec<f64> {
        let mut rng = Pcg64Mcg::seed_from_u64((key << 32) ^ (part << 24) ^ index);
        (0..len).map(|_| uniform(&mut rng, v.sqrt())).collect()
    };
    feed_totals(t, W * W, |pass, cfg| {
        let key = keys[pass as usize];
        let s = (cfg.camera_samples / base.camera_samples) as u64;
        let g = cfg.forward_rays / base.forward_rays;
        let mut x = vec![1.0f64; W * W];
        for j in 0..g {
            let line = draw(key, 1, j, W, b);
            x.iter_mut()
                .enumerate()
                .for_each(|(p, v)| *v += line[p / W] / g as f64);
        }
        for i in 0..s {
            let own = draw(key, 2, i, W * W, a);
            x.iter_mut().zip(&own).for_each(|(v, o)| *v += o / s as f64);
            for j in 0..g {
                let pair = draw(key, 3, (i << 8) | j, W * W, c);
                x.iter_mut()
                    .zip(&pair)
                    .for_each(|(v, o)| *v += o / (s * g) as f64);
            }
        }
        x
    });
}

/// The forward rays' noise is lines, the camera paths' is each pixel's own (`feed_structured`):
/// a block's mean keeps half of the lines (a block spans two of the lattice's rows) and a
/// quarter of the white noise, so the block model gives the camera term half the weight the
/// per-pixel model does, and with it the budgets move towards forward rays: fewer camera paths
/// or more rays, never the other way.
#[test]
fn blocks_see_the_forward_rays_lines_and_pull_the_budgets_to_them() {
    let mut t = auto_tuner_256();
    feed_structured(&mut t, (2.0e-4, 4.0e-4, 2.0e-4));
    let (_, base) = t.measure(Role::Base).expect("measured");
    let (pixel, block) = t.noise_splits(&base).expect("resolved");
    let block = block.expect("the blocks resolve both budgets");
    let ratio = |s: &model::NoiseSplit| s.camera / s.forward;
    // Expected: 2e-4 / (4e-4 x 12 500) per pixel, half of it per block; the estimates carry
    // the lines' noise (128 of them), about 12 % each.
    assert!(ratio(&block) < 0.75 * ratio(&pixel), "{pixel:?} {block:?}");
    let cost = model::CostSplit {
        per_sample: 1.0,
        per_ray: 2e-5,
        per_pair: 2e-6,
    };
    let search = model::BudgetSearch {
        samples: None,
        max_samples: 16,
        rays: None,
        rays_range: (10_000, 200_000),
    };
    let (s1, n1) = model::budgets(&[pixel], &cost, &search);
    let (s2, n2) = model::budgets(&[pixel, block], &cost, &search);
    assert!(
        s1 > 1 && n1 < 198_896,
        "interior per-pixel optimum: {s1} {n1}"
    );
    assert!(
        s2 <= s1 && n2 >= n1 && (s2, n2) != (s1, n1),
        "{s1} {n1} -> {s2} {n2}"
    );
}

/// The fourth pilot (both budgets times `BUDGET_FACTOR`) splits the noise from the pilots'
/// paired differences alone (`NoiseSplit::from_four`). With brume's structure and the forward
/// rays' lines 40 times the camera paths' white noise, the Base pilot's variance is known to
/// about 12 % (128 lines on the lattice), and the three-pilot split this replaced, whose
/// camera term was `s (v - X / n)`, inherited that error times 40 (here it clipped it to 0). The four pilots' combinations cancel
/// the lines: each term must come back within 4 of its standard errors, the camera term
/// resolved (over 4 standard errors).
#[test]
fn the_fourth_pilot_splits_the_noise_without_the_lines_noise() {
    let (a, b, c) = (1.0e-4, 4.0e-3, 1.0e-4);
    let mut t = auto_tuner_256();
    feed_structured(&mut t, (a, b, c));
    // The truth at the Base pilot's budgets (1 camera path, 12 500 rays), summed over the
    // whole image (the lattice's sums times 4), times e^2.
    let whole = (256 * 256) as f64;
    let e2 = (1.0 - 1.0 / BUDGET_FACTOR as f64).powi(2);
    let truth = [a, b, c].map(|x| x * whole * e2);
    let terms = t.four_terms_in(&t.shares).expect("four pilots");
    // The camera and pair terms are white noise, whose standard error `Gain` states; the
    // forward term is 128 lines' variance, known to sqrt(2 / 128) = 12.5 % (`Gain` takes
    // pixels as independent and states less): within 4 of either.
    for i in [0, 2] {
        let g = terms[i];
        assert!(
            (g.gain - truth[i]).abs() < 4.0 * g.se,
            "{terms:?} against {truth:?}"
        );
    }
    assert!(
        (terms[1].gain / truth[1] - 1.0).abs() < 0.5,
        "{terms:?} against {truth:?}"
    );
    assert!(terms[0].gain > 4.0 * terms[0].se, "{terms:?}");
    let (_, base) = t.measure(Role::Base).expect("measured");
    let (pixel, _) = t.noise_splits(&base).expect("resolved");
    let s = t.role_config(Role::Base).expect("base").camera_samples as f64;
    assert!(
        (pixel.camera / s * e2 - terms[0].gain).abs() < 1e-9 * truth[0],
        "{pixel:?}"
    );
}

mod choices;
