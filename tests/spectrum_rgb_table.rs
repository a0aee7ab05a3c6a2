//! The shipped RGB -> spectrum coefficient table is the fit brume would compute itself.

use brume::colour::rgb::{CoefficientTable, FitContext};

#[test]
fn shipped_table_matches_a_fresh_fit() {
    let shipped = CoefficientTable::from_bytes(include_bytes!("../spectra/srgb-coefficients.bin"))
        .expect("spectra/srgb-coefficients.bin is malformed: regenerate it with `cargo run --release --example make_rgb_table`");
    let fresh = CoefficientTable::compute(FitContext::srgb().expect("colour data"));
    let diff = shipped.max_difference(&fresh);
    assert!(
        diff < 1e-9,
        "shipped table differs from the fit by {diff}: regenerate it"
    );
}

#[test]
fn malformed_tables_are_rejected() {
    assert!(CoefficientTable::from_bytes(&[0u8; 16]).is_none());
    let mut nan = vec![0u8; 3 * 32 * 32 * 32 * 3 * 8];
    nan[..8].copy_from_slice(&f64::NAN.to_le_bytes());
    assert!(CoefficientTable::from_bytes(&nan).is_none());
}
