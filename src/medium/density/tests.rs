//! The change of variable: `depth` is the integral of the density along the ray (against
//! quadrature of `at`), and `distance` inverts it.

use super::*;

fn fields() -> Vec<Density> {
    vec![
        Density::Height(Height::new(0.5, 2.0, Vec3::new(0.0, 1.0, 0.0))),
        Density::Height(Height::new(-3.0, 0.7, Vec3::new(0.3, 1.0, -0.2))),
        Density::Layer(Layer::new(1.0, 0.8, Vec3::new(0.0, 1.0, 0.0))),
        Density::Layer(Layer::new(-0.5, 3.0, Vec3::new(0.1, 0.9, 0.4))),
    ]
}

fn rays() -> Vec<(Vec3, Vec3)> {
    let dirs = [
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::new(0.0, -1.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.6, 0.3, -0.2),
        Vec3::new(-0.2, -0.7, 0.5),
        Vec3::new(1.0, 1e-7, 0.0),
    ];
    let origins = [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 1.2, -2.0),
        Vec3::new(0.0, -2.0, 1.0),
    ];
    origins
        .iter()
        .flat_map(|o| dirs.iter().map(move |d| (*o, d.normalize())))
        .collect()
}

/// Composite Simpson of the density along the ray, in f64.
fn quadrature(f: &Density, o: Vec3, d: Vec3, s: f32) -> f64 {
    let n = 4000;
    let h = s as f64 / n as f64;
    (0..=n)
        .map(|i| {
            let w = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            w * f.at(o + d * (i as f64 * h) as f32) as f64
        })
        .sum::<f64>()
        * h
        / 3.0
}

#[test]
fn depth_is_the_integral_of_the_density() {
    for f in fields() {
        for (o, d) in rays() {
            let along = f.along(o, d);
            for s in [0.01f32, 0.7, 2.5, 6.0] {
                let want = quadrature(&f, o, d, s);
                let got = along.depth(s) as f64;
                assert!(
                    (got - want).abs() <= 2e-5 * want.max(1e-3),
                    "{f:?} o {o} d {d} s {s}: depth {got}, quadrature {want}"
                );
                let rho = along.rho(s);
                assert!((rho - f.at(o + d * s)).abs() <= 1e-5 * rho.max(1.0));
            }
        }
    }
}

#[test]
fn distance_inverts_depth() {
    for f in fields() {
        for (o, d) in rays() {
            let along = f.along(o, d);
            for s in [0.001f32, 0.3, 1.7, 4.0, 9.0] {
                let u = along.depth(s);
                if u <= 0.0 || along.rho(s) < 1e-3 {
                    continue;
                }
                let back = along.distance(u);
                assert!(
                    (back - s).abs() <= 1e-4 * s.max(1.0),
                    "{f:?} o {o} d {d}: s {s} -> u {u} -> {back}"
                );
            }
            // Past the whole depth ahead the distance is infinite.
            let all = along.depth(f32::INFINITY);
            if all.is_finite() {
                assert_eq!(
                    along.distance(all * 1.01 + 1e-3),
                    f32::INFINITY,
                    "{f:?} d {d}"
                );
            }
        }
    }
}

#[test]
fn uniform_is_the_identity() {
    let a = Density::Uniform.along(Vec3::ZERO, Vec3::X);
    for s in [0.0f32, 1e-7, 0.3, 7.25, f32::INFINITY] {
        assert_eq!(a.depth(s).to_bits(), s.to_bits());
        assert_eq!(a.distance(s).to_bits(), s.to_bits());
    }
}

#[test]
fn descriptions_are_checked() {
    let bad = DensityDesc::Height {
        base: 0.0,
        scale_height: 0.0,
        up: [0.0, 0.0, 0.0],
    };
    let keys: Vec<String> = bad.check().into_iter().map(|(k, _)| k).collect();
    assert_eq!(keys, ["scale_height", "up"]);
    let bad = DensityDesc::Layer {
        top: f32::NAN,
        transition: -1.0,
        up: [0.0, 1.0, 0.0],
    };
    let keys: Vec<String> = bad.check().into_iter().map(|(k, _)| k).collect();
    assert_eq!(keys, ["top", "transition"]);
    let (lo, hi) = DensityDesc::Layer {
        top: 1.0,
        transition: 1.0,
        up: [0.0, 1.0, 0.0],
    }
    .build(&|f| f.into(), None)
    .unwrap()
    .range(Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 3.0, 1.0));
    assert_eq!((lo, hi), (0.0, 1.0));
}
