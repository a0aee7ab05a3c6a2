//! What `brume info` says of each medium's density field: the range of density over the
//! scene's bounds (a box around every shape, so around every medium bounded by shapes), the
//! memory the field takes, and the meteorological optical range at the least and greatest
//! density (the visibility a field of that density everywhere would give).

use crate::colour::photometry::meteorological_optical_range;
use crate::world::Scene;

/// One line per medium with a density field (media in id order, named by `names`).
pub fn density_report(scene: &Scene, names: &[&str]) -> Vec<String> {
    let b = scene.geometry.bounds();
    let (lo, hi) = (b.min, b.max);
    let mut out = Vec::new();
    for (m, name) in scene.media.iter().zip(names) {
        if m.density.is_uniform() {
            continue;
        }
        let (rmin, rmax) = m.density.range(lo, hi);
        let mor = |rho: f32| {
            let st = m.sigma_t * rho;
            match meteorological_optical_range(st.as_slice(scene.grid.n), &scene.grid) {
                Ok(Some(d)) => format!("{d:.4} m"),
                Ok(None) => "unbounded".to_string(),
                Err(e) => format!("unknown ({e})"),
            }
        };
        let tracking = match &m.tracking {
            None => "exact optical depth".to_string(),
            Some(t) => format!(
                "delta tracking against {} majorant blocks ({} bytes)",
                t.blocks(),
                t.bytes()
            ),
        };
        out.push(format!(
            "medium {name}: density {}; from {rmin:.4e} to {rmax:.4e} over the scene's bounds; \
             memory: {} bytes; visibility {} at the greatest density, {} at the \
             least; transport: {tracking}",
            m.density.describe(),
            m.density.bytes(),
            mor(rmax),
            mor(rmin)
        ));
    }
    out
}
