//! The estimates nested in a pass (`integrator::nest`) against passes of their own
//! configurations: rendered on shipped scenes, both must have the same mean and variance.

use std::path::Path;
use std::sync::atomic::AtomicBool;

use super::Renderer;

mod blend;
use crate::integrator::auto::{PassConfig, pixel_totals};
use crate::integrator::nest::{Nest, Variant};
use crate::scene::{build, build_integrator, load};

/// Passes of each kind: the variance ratio of two sets of 64 passes lies within [0.43, 2.3]
/// with probability 0.999 (F distribution, 63 and 63 degrees of freedom).
const PASSES: u64 = 64;

/// Mean and variance (over passes) of each pass's image total.
fn stats(x: &[f64]) -> (f64, f64) {
    let m = x.iter().sum::<f64>() / x.len() as f64;
    let v = x.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (x.len() - 1) as f64;
    (m, v)
}

/// Renders `PASSES` passes of `file` at (k s, k n) with the four budget estimates nested, and
/// `PASSES` passes of their own at (s, n), (s, k n) and (k s, n), each with its own random
/// numbers. Every nested estimate's image total has the mean of its own passes' (within 4
/// standard errors of the difference) and their variance (the F bound above), and the
/// nest's (s, n) estimate is far from the pass's own: a wrong factor (4 or 16) cannot pass.
fn nested_estimates_match_their_own_passes(file: &str, sets: &[&str]) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(file);
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let loaded = load(&path, &sets).expect("a shipped scene");
    let scene = build(&loaded).expect("builds");
    let integrator = build_integrator(&loaded, &scene).expect("an integrator");
    let (s, n, k) = (1u32, 2000u64, 4u32);
    let q = integrator.q.clone();
    let config = |paths: u32, rays: u64| PassConfig {
        q: q.clone(),
        forward_rays: rays,
        camera_samples: paths,
        indirect_scale: 1.0,
    };
    let v = |sub_paths, sub_rays| Variant {
        sub_paths,
        sub_rays,
    };
    let nest = Nest {
        paths: s,
        rays: n,
        path_factor: k as f32,
        ray_factor: k as f32,
        variants: vec![v(true, true), v(true, false), v(false, true)],
    };
    let own = [config(s, n), config(s, n * k as u64), config(s * k, n)];
    let mut r = Renderer::new(&scene, integrator, 5);
    let stop = AtomicBool::new(false);
    let top = config(s * k, n * k as u64);
    r.integrator.apply(&top, &scene.media).expect("applies");
    let mut nested = vec![Vec::new(); 4];
    for p in 0..PASSES {
        let (buf, ..) = r
            .render_sampled((1, p), 0, Some(&nest), &stop)
            .expect("rendered");
        let main: f64 = pixel_totals(&buf.data, buf.pixels, buf.n).iter().sum();
        nested[3].push(main);
        for (j, t) in buf.variants.chunks_exact(buf.pixels).enumerate() {
            nested[j].push(t.iter().sum());
        }
    }
    for (j, c) in own.iter().enumerate() {
        r.integrator.apply(c, &scene.media).expect("applies");
        let totals: Vec<f64> = (0..PASSES)
            .map(|p| {
                let (buf, ..) = r
                    .render_sampled((1, 1000 + p), 0, None, &stop)
                    .expect("rendered");
                pixel_totals(&buf.data, buf.pixels, buf.n).iter().sum()
            })
            .collect();
        let ((m_nest, v_nest), (m_own, v_own)) = (stats(&nested[j]), stats(&totals));
        let se = ((v_nest + v_own) / PASSES as f64).sqrt();
        let z = (m_nest - m_own) / se;
        assert!(
            z.abs() < 4.0,
            "{file} {c:?}: nested {m_nest} against {m_own} (z {z})"
        );
        assert!(
            se < 0.1 * m_own,
            "{file} {c:?}: the means are not tested (se {se} of {m_own})"
        );
        let ratio = v_nest / v_own;
        assert!(
            (0.43..2.3).contains(&ratio),
            "{file} {c:?}: variance {v_nest} nested, {v_own} alone"
        );
    }
    // The (s, n) estimate is not the whole pass's in disguise: its variance is several times
    // the pass's (a quarter of the camera paths and a quarter of the rays).
    assert!(stats(&nested[0]).1 > 2.0 * stats(&nested[3]).1);
}

/// Surfaces, a medium and next-event estimation (a directional light, an orthographic camera).
#[test]
fn nested_estimates_in_fog_cube() {
    nested_estimates_match_their_own_passes(
        "fog-cube.toml",
        &["camera.width=16", "camera.height=16", "integrator.q=0.5"],
    );
}

/// A spot lamp through a glass sphere: caustic light splats to the perspective camera.
#[test]
fn nested_estimates_in_glass_sphere_fog() {
    nested_estimates_match_their_own_passes(
        "glass-sphere-fog.toml",
        &["camera.width=24", "camera.height=18"],
    );
}

/// Two point lamps over a street.
#[test]
fn nested_estimates_in_street_fog() {
    nested_estimates_match_their_own_passes(
        "street-fog.toml",
        &["camera.width=32", "camera.height=18"],
    );
}
