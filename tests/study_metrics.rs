//! The study's error metrics, efficiency, reference file round trip and variant expansion on
//! known inputs (exact values, no Monte Carlo).

use brume::film::SpectralImage;
use brume::spectrum::SpectralGrid;
use brume::study::{
    Reference, efficiency, expand, layer_errors, mean_error, mean_noise, mse, parse_vary, rel_mse,
    rmse,
};

fn close(a: f64, b: f64) {
    assert!((a - b).abs() <= 1e-12 * b.abs().max(1.0), "{a} != {b}");
}

#[test]
fn rmse_and_mse_of_known_images() {
    let r = [1.0f32, 2.0, 3.0, 4.0];
    let x = [1.0f32, 3.0, 1.0, 4.0];
    // Errors 0, 1, -2, 0: MSE = 5/4.
    close(mse(&x, &r), 1.25);
    close(rmse(&x, &r), 1.25f64.sqrt());
    close(mse(&r, &r), 0.0);
    // Signed: (0 + 1 - 2 + 0) / 4.
    close(mean_error(&x, &r), -0.25);
    let e = layer_errors(&x, &r);
    close(e.mse, 1.25);
    close(e.rmse, 1.25f64.sqrt());
}

#[test]
fn rel_mse_of_known_images() {
    let r = [1.0f32, 2.0, 3.0, 4.0];
    let x = [1.0f32, 3.0, 1.0, 4.0];
    // eps = 1 % of mean |r| = 0.025.
    let eps2 = 0.025f64 * 0.025;
    let want = (1.0 / (4.0 + eps2) + 4.0 / (9.0 + eps2)) / 4.0;
    close(rel_mse(&x, &r), want);
    // Scale invariant: both images times 1000 give the same value.
    let r2: Vec<f32> = r.iter().map(|v| v * 1000.0).collect();
    let x2: Vec<f32> = x.iter().map(|v| v * 1000.0).collect();
    assert!((rel_mse(&x2, &r2) - want).abs() < 1e-9);
    // A zero reference pixel does not make it infinite.
    assert!(rel_mse(&[1.0, 1.0], &[0.0, 1.0]).is_finite());
}

#[test]
fn efficiency_is_inverse_of_mse_times_time() {
    close(efficiency(0.5, 4.0), 0.5);
    close(efficiency(2e-3, 10.0), 50.0);
    // Halving the error at twice the time keeps the efficiency: 1/time convergence.
    close(efficiency(1e-2, 1.0), efficiency(5e-3, 2.0));
    assert!(efficiency(0.0, 1.0).is_infinite());
}

#[test]
fn mean_noise_averages_standard_errors() {
    let grid = SpectralGrid::new(2, 380.0, 780.0);
    let mut img = SpectralImage::new(2, 1, grid);
    assert_eq!(mean_noise(&img), 0.0);
    img.noise = Some(vec![0.1, 0.2, 0.3, 0.4]);
    let want = [0.1f32, 0.2, 0.3, 0.4]
        .iter()
        .map(|&v| v as f64)
        .sum::<f64>()
        / 4.0;
    close(mean_noise(&img), want);
}

#[test]
fn reference_round_trips_exactly() {
    let grid = SpectralGrid::new(3, 400.0, 700.0);
    let mut img = SpectralImage::new(2, 2, grid);
    img.data = (0..12).map(|i| i as f32 * 0.37 + 1e-9).collect();
    img.noise = Some((0..12).map(|i| i as f32 * 0.01).collect());
    img.layers = vec![
        ("medium".into(), (0..12).map(|i| i as f32 * 0.1).collect()),
        ("surface".into(), (0..12).map(|i| i as f32 * 0.27).collect()),
    ];
    let r = Reference::from_image(&img, 17, 3.5);
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("reference.bin");
    r.save(&p).unwrap();
    let back = Reference::load(&p).unwrap();
    assert_eq!(back, r);
    close(
        r.noise_mse()
            .expect("a rendered reference has its standard error"),
        (0..12)
            .map(|i| ((i as f32 * 0.01) as f64).powi(2))
            .sum::<f64>()
            / 12.0,
    );
    // A truncated file is an error, not a panic.
    let bytes = std::fs::read(&p).unwrap();
    std::fs::write(&p, &bytes[..bytes.len() - 4]).unwrap();
    assert!(Reference::load(&p).is_err());
    std::fs::write(&p, b"not a reference").unwrap();
    assert!(Reference::load(&p).is_err());
}

#[test]
fn variants_are_the_cartesian_product() {
    let a = parse_vary("integrator.q=1,0.3, 0.1").unwrap();
    assert_eq!(a.values, vec!["1", "0.3", "0.1"]);
    let b = parse_vary("integrator.volume=spheres,cylinder").unwrap();
    let v = expand(&[a, b]);
    assert_eq!(v.len(), 6);
    assert_eq!(v[0].label, "q=1 volume=spheres");
    assert_eq!(v[1].label, "q=1 volume=cylinder");
    assert_eq!(
        v[5].sets,
        vec!["integrator.q=0.1", "integrator.volume=cylinder"]
    );
    assert!(parse_vary("integrator.q").is_err());
    assert!(parse_vary("integrator.q=").is_err());
    assert!(parse_vary("=1,2").is_err());
    assert_eq!(expand(&[]).len(), 1);
}
