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

// ---- Spectral grids with lines -------------------------------------------------------------

use brume::colour::{Observer, XyzWeights};
use brume::spectrum::{Bin, GridError, LINE_WIDTH, MAX_BINS, Spectrum, lines};

/// Grids with lines in awkward places: on an equal edge (530 = 380 + 12 x 12.5), a hair from
/// one, two lines closer than a line width, at and next to the ends of the range, and bins
/// narrower than a line.
fn line_grids() -> Vec<(usize, f64, f64, Vec<f64>)> {
    vec![
        (32, 380.0, 780.0, vec![532.0]),
        (32, 380.0, 780.0, vec![530.0]),
        (32, 380.0, 780.0, vec![530.03, 633.0, 450.0]),
        (32, 380.0, 780.0, vec![532.0, 532.05, 532.0]),
        (32, 380.0, 780.0, vec![380.0, 780.0]),
        (32, 380.0, 780.0, vec![380.07, 779.99]),
        (24, 380.0, 780.0, vec![405.0, 445.5, 589.0, 589.6, 656.3]),
        (16, 500.0, 500.5, vec![500.2]),
    ]
}

#[test]
fn line_grids_cover_the_range_without_gaps_or_overlaps() {
    for (uniform, lo, hi, ls) in line_grids() {
        let g = SpectralGrid::with_lines(uniform, lo, hi, &ls).unwrap();
        let equal = SpectralGrid::new(uniform, lo, hi);
        let ctx = format!("{uniform} bins over {lo}-{hi} with lines {ls:?}");
        assert!(g.n <= MAX_BINS, "{ctx}: {} bins", g.n);
        assert_eq!(g.edges(0).0, lo, "{ctx}");
        assert_eq!(g.edges(g.n - 1).1, hi, "{ctx}");
        let mut total = 0.0;
        for i in 0..g.n {
            let (a, b) = g.edges(i);
            assert!(b > a, "{ctx}: bin {i} is empty");
            assert_eq!(g.bin_width(i), b - a, "{ctx}: bin {i}");
            if i + 1 < g.n {
                assert_eq!(b, g.edges(i + 1).0, "{ctx}: gap or overlap after bin {i}");
            }
            if let Bin::Band { .. } = g.bin(i) {
                // No sliver bands: at least half a line width (or half an equal bin).
                let eps = 0.5 * LINE_WIDTH.min(equal.bin_width(0));
                assert!(b - a >= eps * 0.999, "{ctx}: sliver band {a}-{b}");
            }
            total += b - a;
        }
        assert!(
            (total - (hi - lo)).abs() < 1e-9,
            "{ctx}: widths sum to {total}"
        );
        for &l in &ls {
            let i = g
                .line_bin(l)
                .unwrap_or_else(|| panic!("{ctx}: no bin for {l}"));
            assert_eq!(g.bin_of(l), Some(i), "{ctx}");
            let (a, b) = g.edges(i);
            assert!(
                a <= l && l <= b && b - a <= 1.5 * LINE_WIDTH,
                "{ctx}: {a}-{b}"
            );
            assert_eq!(
                g.bin(i),
                Bin::Line {
                    lambda: l,
                    lo: a,
                    hi: b
                }
            );
            assert_eq!(g.centre(i), l);
        }
        // Equal edges away from every line keep their exact values.
        for k in 1..uniform {
            let e = equal.edges(k).0;
            if ls.iter().all(|l| (e - l).abs() > LINE_WIDTH) {
                assert!((0..g.n).any(|i| g.edges(i).0 == e), "{ctx}: lost edge {e}");
            }
        }
    }
}

#[test]
fn a_grid_without_lines_is_the_equal_grid_exactly() {
    let g = SpectralGrid::with_lines(24, 380.0, 780.0, &[]).unwrap();
    let e = SpectralGrid::new(24, 380.0, 780.0);
    assert_eq!(g, e);
    for i in 0..24 {
        let w = (780.0 - 380.0) / 24.0;
        assert_eq!(
            g.edges(i),
            (380.0 + w * i as f64, 380.0 + w * (i + 1) as f64)
        );
        assert_eq!(g.bin_width(i), w);
    }
    assert!(g.lines().is_empty() && g.uniform_bins() == 24);
}

#[test]
fn bad_lines_are_errors() {
    let grid = |ls: &[f64]| SpectralGrid::with_lines(32, 380.0, 780.0, ls);
    assert!(matches!(grid(&[1064.0]), Err(GridError::Outside { .. })));
    assert!(matches!(
        grid(&[-532.0]),
        Err(GridError::NotAWavelength { .. })
    ));
    assert!(matches!(
        grid(&[f64::NAN]),
        Err(GridError::NotAWavelength { .. })
    ));
    assert!(matches!(
        grid(&[532.0, 532.001]),
        Err(GridError::TooClose { .. })
    ));
    // Each line inside an equal bin adds two bins: 16 lines fit in 64, a 17th does not.
    let many: Vec<f64> = (0..17).map(|k| 386.0 + 12.5 * k as f64).collect();
    assert_eq!(grid(&many[..16]).unwrap().n, 64);
    let e = grid(&many).unwrap_err();
    assert!(
        matches!(e, GridError::TooManyBins { needed: 66, .. }),
        "{e}"
    );
}

#[test]
fn line_bins_hold_values_at_the_line_and_lines_keep_their_power() {
    let g = SpectralGrid::with_lines(32, 380.0, 780.0, &[532.0, 633.3]).unwrap();
    let i = g.line_bin(532.0).unwrap();
    // A reflectance with a kink at the line: the band average would differ, the line's
    // value must not.
    let r = pl(&[380.0, 532.0, 780.0], &[0.2, 0.9, 0.1]);
    assert_eq!(r.bin_averages(&g, Extrapolation::Clamp)[i], 0.9);
    let ints = r.bin_integrals(&g, Extrapolation::Clamp);
    assert!((ints[i] - 0.9 * g.bin_width(i)).abs() < 1e-15);
    // Bands stay exact averages.
    let b = r.bin_averages(&g, Extrapolation::Clamp);
    for k in (0..g.n).filter(|&k| matches!(g.bin(k), Bin::Band { .. })) {
        let (a, z) = g.edges(k);
        let want = quad(|l| r.eval(l, Extrapolation::Clamp), a, z) / (z - a);
        assert!((b[k] as f64 - want).abs() < 1e-5, "band {k}");
    }
    let p = power_law(2.0, 550.0, 4.0, &g);
    assert!((p[i] as f64 - 2.0 * (532.0f64 / 550.0).powi(-4)).abs() < 1e-6);
    // Lines' powers come back from the grid's integral (value x width summed).
    let s = lines(&[(532.0, 1.0), (633.3, 0.25)], &g).unwrap();
    assert!((g.integral(&s) - 1.25).abs() < 1e-6, "{}", g.integral(&s));
    assert!(
        lines(&[(600.0, 1.0)], &g).is_err(),
        "no bin for a line the grid lacks"
    );
}

/// colour-science 0.4.7, `colour.XYZ_to_xy(colour.wavelength_to_XYZ(532))` with the CIE 1931
/// 2 degree observer (its 1 nm table holds 532 nm: x-bar 0.18914, y-bar 0.8849624, z-bar
/// 0.03693564).
const XY_532: [f64; 2] = [0.170_237_2, 0.796_518_5];

fn xy(xyz: [f64; 3]) -> [f64; 2] {
    let s = xyz[0] + xyz[1] + xyz[2];
    [xyz[0] / s, xyz[1] / s]
}

#[test]
fn a_line_has_the_chromaticity_of_its_wavelength() {
    let g = SpectralGrid::with_lines(32, 380.0, 780.0, &[532.0]).unwrap();
    let w = XyzWeights::new(Observer::Cie1931, &g).unwrap();
    let got = xy(w.xyz_of(&lines(&[(532.0, 1.0)], &g).unwrap()));
    assert!(
        (got[0] - XY_532[0]).abs() < 1e-6 && (got[1] - XY_532[1]).abs() < 1e-6,
        "{got:?}"
    );
    // The same power in the 12.5 nm bin around 532 (the grid without lines) is far off.
    let e = SpectralGrid::default();
    let bin = e.bin_of(532.0).unwrap();
    let before = xy(XyzWeights::new(Observer::Cie1931, &e)
        .unwrap()
        .xyz_of(&Spectrum::single(bin, 1.0)));
    assert!((before[0] - XY_532[0]).abs() > 0.02, "{before:?}");
}
