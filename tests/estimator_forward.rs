//! Forward (light) free flights with the spectral mixture (FMCRT), per bin against analytic
//! values: the escaping flux `Phi_l e^{-st_l T}`, the scattered flux per distance interval
//! `Phi_l ∫ ss_l e^{-st_l t} dt` (absorption by weight), and the flux
//! seen by a gather point at distance s along the segment, `Phi_l e^{-st_l s}`.
//! z-bound: |z| < 4 in every bin and every tally.

#[path = "estimator_stats.rs"]
mod stats;

use brume::medium::{FlightEnd, ForwardFlight, Medium};
use brume::spectrum::Spectrum;
use rand::SeedableRng;
use rand_pcg::Pcg64Mcg;
use stats::Acc;

const N: usize = 4;
const ST: [f32; N] = [0.1, 1.0, 3.0, 12.0];
const ALB: [f32; N] = [0.9, 0.3, 0.99, 0.6];
const PHI: [f32; N] = [1.0, 0.1, 3.0, 0.5];
const T: f32 = 0.8;
/// Interval edges for the collision tally.
const EDGES: [f32; 4] = [0.0, 0.05, 0.3, T];
/// Gather points along the segment.
const PROBES: [f32; 3] = [0.02, 0.25, 0.7];

fn medium() -> Medium {
    Medium::from_extinction_albedo(&ST, &ALB, 0.2).unwrap()
}

#[test]
fn forward_flights_are_unbiased_per_bin() {
    let m = medium();
    let phi = Spectrum::from_slice(&PHI);
    let mut rng = Pcg64Mcg::seed_from_u64(600);
    // Tallies: escape, 3 collision intervals, 3 probes, all per bin.
    let mut tallies: Vec<Acc> = (0..7).map(|_| Acc::new(N)).collect();
    let mut killed = 0u64;
    let rays = 400_000;
    for _ in 0..rays {
        let flight = ForwardFlight::sample(&m, &phi, 0.1, T, &mut rng);
        let mut rows = vec![[0.0f64; N]; 7];
        for (k, &s) in PROBES.iter().enumerate() {
            if flight.end() >= s {
                let f = flight.flux_at(&phi, s);
                for l in 0..N {
                    rows[4 + k][l] = f[l] as f64;
                }
            }
        }
        let mut flux = phi;
        match flight.finish(&m, &mut flux) {
            FlightEnd::Escaped => {
                for l in 0..N {
                    rows[0][l] = flux[l] as f64;
                }
            }
            FlightEnd::Scattered { t } => {
                let k = EDGES
                    .windows(2)
                    .position(|e| t >= e[0] && t < e[1])
                    .unwrap();
                for l in 0..N {
                    rows[1 + k][l] = flux[l] as f64;
                }
            }
            FlightEnd::Killed { .. } => killed += 1,
        }
        for (acc, row) in tallies.iter_mut().zip(&rows) {
            acc.add(row);
        }
    }
    // Only an underflowing mixture density kills a flight; none at these depths.
    assert_eq!(killed, 0);
    for l in 0..N {
        let (st, ss, p) = (ST[l] as f64, (ST[l] * ALB[l]) as f64, PHI[l] as f64);
        let mut exact = vec![p * (-st * T as f64).exp()];
        for e in EDGES.windows(2) {
            exact.push(p * ss / st * ((-st * e[0] as f64).exp() - (-st * e[1] as f64).exp()));
        }
        for &s in &PROBES {
            exact.push(p * (-st * s as f64).exp());
        }
        for (k, acc) in tallies.iter().enumerate() {
            let z = acc.z(l, exact[k]);
            assert!(
                z.abs() < 4.0,
                "tally {k} bin {l}: {} vs {} (z={z})",
                acc.mean(l),
                exact[k]
            );
        }
    }
}
