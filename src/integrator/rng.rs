//! Random streams derived from (seed, pass, domain, index), never from thread identity, so a
//! render is bit-identical whatever the thread count.

use rand::SeedableRng;
use rand_pcg::Pcg64Mcg;

pub type Rng = Pcg64Mcg;

/// Which part of a pass a stream serves; keeps camera and light streams independent.
#[derive(Clone, Copy, Debug)]
#[repr(u64)]
pub enum Domain {
    Camera = 1,
    Light = 2,
    Sensor = 3,
}

fn splitmix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

pub fn stream(seed: u64, pass: u64, domain: Domain, index: u64) -> Rng {
    let a = splitmix(seed ^ splitmix(pass.wrapping_add(0x1234_5678)));
    let b = splitmix(a ^ splitmix(domain as u64).wrapping_add(index));
    let c = splitmix(b ^ index.rotate_left(29));
    Pcg64Mcg::seed_from_u64(c ^ (b << 1))
}
