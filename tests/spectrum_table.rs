//! Spectral data: CSV parsing errors, exact bin integration, built-ins, analytic spectra.

use brume::spectrum::{
    Extrapolation, PiecewiseLinear, SpectralGrid, SpectralTable, SpectrumError, builtin_names,
    power_law, resolve,
};

fn pl(w: &[f64], v: &[f64]) -> PiecewiseLinear {
    PiecewiseLinear::new(w.to_vec(), v.to_vec())
}

/// Midpoint rule with many steps: an independent estimate of the integral.
fn quad(f: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    let n = 20_000;
    let h = (b - a) / n as f64;
    (0..n).map(|k| f(a + (k as f64 + 0.5) * h)).sum::<f64>() * h
}

#[test]
fn integral_is_exact_for_piecewise_linear_data() {
    let s = pl(
        &[400.0, 437.0, 500.0, 611.5, 700.0],
        &[0.0, 2.0, 0.5, 1.5, 1.0],
    );
    for ext in [Extrapolation::Zero, Extrapolation::Clamp] {
        for (a, b) in [
            (380.0, 780.0),
            (410.0, 415.0),
            (436.0, 612.0),
            (650.0, 720.0),
        ] {
            let exact = s.integral(a, b, ext);
            // Split the reference quadrature at the knots, where Zero extrapolation jumps.
            let mut cuts = vec![a];
            cuts.extend(s.wavelengths.iter().copied().filter(|&w| w > a && w < b));
            cuts.push(b);
            let num: f64 = cuts
                .windows(2)
                .map(|c| quad(|l| s.eval(l, ext), c[0], c[1]))
                .sum();
            assert!(
                (exact - num).abs() < 1e-6,
                "{ext:?} [{a},{b}]: {exact} vs {num}"
            );
        }
    }
}

#[test]
fn extrapolation_zero_and_clamp() {
    let s = pl(&[500.0, 600.0], &[1.0, 3.0]);
    assert_eq!(s.integral(400.0, 500.0, Extrapolation::Zero), 0.0);
    assert!((s.integral(400.0, 500.0, Extrapolation::Clamp) - 100.0).abs() < 1e-12);
    assert!((s.integral(600.0, 650.0, Extrapolation::Clamp) - 150.0).abs() < 1e-12);
    assert!((s.integral(500.0, 600.0, Extrapolation::Zero) - 200.0).abs() < 1e-12);
}

#[test]
fn bin_average_of_a_linear_function_is_its_centre_value() {
    let s = pl(&[300.0, 900.0], &[0.0, 6.0]);
    let g = SpectralGrid::new(13, 380.0, 780.0);
    let b = s.bin_averages(&g, Extrapolation::Zero);
    for i in 0..g.n {
        let want = s.eval(g.centre(i), Extrapolation::Zero);
        assert!((b[i] as f64 - want).abs() < 1e-5, "bin {i}");
    }
    assert!(
        b.as_slice(64)[g.n..].iter().all(|&x| x == 0.0),
        "lanes past n stay 0"
    );
}

fn parse_err(text: &str) -> String {
    SpectralTable::parse(text, "t.csv", false)
        .unwrap_err()
        .to_string()
}

#[test]
fn parse_errors_name_file_and_line() {
    let head = "# c\nwavelength_nm,r\n400,1\n";
    let e = parse_err(&format!("{head}400,2\n"));
    assert!(
        e.starts_with("t.csv:4:") && e.contains("strictly increasing"),
        "{e}"
    );
    let e = parse_err(&format!("{head}\n500,-1\n"));
    assert!(e.starts_with("t.csv:5:") && e.contains("negative"), "{e}");
    let e = parse_err(&format!("{head}500,NaN\n"));
    assert!(e.starts_with("t.csv:4:") && e.contains("not finite"), "{e}");
    let e = parse_err(&format!("{head}500,inf\n"));
    assert!(e.contains("not finite"), "{e}");
    let e = parse_err("nm,r\n400,1\n");
    assert!(
        e.starts_with("t.csv:1:") && e.contains("wavelength_nm"),
        "{e}"
    );
    let e = parse_err("wavelength_nm,r\n400,1\n");
    assert!(e.contains("at least two"), "{e}");
    // Negative values are fine where the caller allows them.
    assert!(SpectralTable::parse(&format!("{head}500,-1\n"), "t.csv", true).is_ok());
}

#[test]
fn builtins_resolve_by_name_and_column() {
    for name in builtin_names() {
        assert!(resolve(name, None, false).is_ok(), "{name}");
    }
    let by_name = resolve("colorchecker:dark_skin", None, false).unwrap();
    let by_index = resolve("colorchecker:1", None, false).unwrap();
    assert_eq!(by_name, by_index);
    assert!((by_name.eval(380.0, Extrapolation::Clamp) - 0.048).abs() < 1e-12);
    let e = resolve("colorchecker:nope", None, false).unwrap_err();
    assert!(matches!(e, SpectrumError::NoColumn { .. }) && e.to_string().contains("dark_skin"));
    assert!(resolve("no-such-spectrum", None, false).is_err());
}

#[test]
fn power_law_bin_averages_are_exact() {
    let g = SpectralGrid::new(16, 380.0, 780.0);
    for p in [0.0, 1.0, 4.0, -0.5] {
        let s = power_law(2.0, 550.0, p, &g);
        for i in 0..g.n {
            let (a, b) = g.edges(i);
            let want = quad(|l| 2.0 * (l / 550.0f64).powf(-p), a, b) / (b - a);
            assert!(((s[i] as f64) - want).abs() < 1e-5 * want, "p={p} bin {i}");
        }
    }
}
