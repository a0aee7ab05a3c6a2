//! Paper eq. 3 ("long" forward segments: deterministic attenuation along the forward ray) proved
//! against eq. 2: eq. 2 applied to forward segments that end at a sampled extinction
//! (t ~ st e^{-st t}) has, averaged over the extinction, exactly the long estimator's mean.
//!
//! Finding: the printed eq. 3 (denominator 1 + |u.v|) agrees for forward rays moving away from
//! the camera (u.v > 0) and is wrong for u.v < 0 (the exact denominator is 1 + u.v, signed);
//! `long_eq3_exact` agrees everywhere. z-bounds: |z| < 4 where they agree, |z| > 10 where not.

#[path = "estimator_stats.rs"]
mod stats;

use brume::integrator::volume::{
    CameraAxis, cylinder_eq2, long_eq3_exact, long_eq3_paper, segment_cylinder,
};
use brume::medium::HomogeneousMedium;
use brume::spectrum::Spectrum;
use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use stats::Acc;

const ST: f32 = 1.5;
const R: f32 = 0.3;

#[test]
fn eq3_against_eq2_with_sampled_forward_extinction() {
    let m = HomogeneousMedium::new(
        &Spectrum::splat(1.0, 1),
        &Spectrum::splat(ST - 1.0, 1),
        0.0,
        1,
    )
    .unwrap();
    let axis = CameraAxis {
        origin: Vec3::ZERO,
        dir: Vec3::Z,
        len: 2.0,
    };
    // (u.v, forward origin): oblique away from / towards the camera, and head-on towards it.
    let cases = [
        (0.6f32, Vec3::new(-0.4, 0.1, 0.2)),
        (-0.6, Vec3::new(-0.4, 0.1, 1.8)),
        (-1.0, Vec3::new(0.1, 0.0, 2.3)),
    ];
    let mut rng = Pcg64Mcg::seed_from_u64(1000);
    for (uv, o0) in cases {
        let s = (1.0 - uv * uv).max(0.0).sqrt();
        let v = Vec3::new(s, 0.0, uv);
        // Start the forward ray 0.3 before o0 so that it enters the cylinder after some travel.
        let o = o0 - v * 0.3;
        let full =
            segment_cylinder(&axis, R, o, v, 100.0).expect("the test ray must hit the cylinder");
        let paper = long_eq3_paper(&m, &full, R)[0] as f64;
        let exact = long_eq3_exact(&m, &full, R)[0] as f64;
        let mut acc = Acc::new(1);
        for _ in 0..200_000 {
            let t = -(1.0 - rng.random::<f32>()).ln() / ST;
            let x =
                segment_cylinder(&axis, R, o, v, t).map_or(0.0, |ch| cylinder_eq2(&m, &ch, R)[0]);
            acc.add(&[x as f64]);
        }
        let (zp, ze) = (acc.z(0, paper), acc.z(0, exact));
        eprintln!(
            "u.v={uv}: eq2 MC {:.5}, eq3 paper {paper:.5} (z={zp:.1}), exact {exact:.5} (z={ze:.1})",
            acc.mean(0)
        );
        assert!(ze.abs() < 4.0, "u.v={uv}: exact long estimator z={ze}");
        if uv > 0.0 {
            assert!(zp.abs() < 4.0, "u.v={uv}: paper eq. 3 z={zp}");
        } else {
            assert!(
                zp.abs() > 10.0,
                "u.v={uv}: paper eq. 3 expected to be wrong, z={zp}"
            );
        }
    }
}
