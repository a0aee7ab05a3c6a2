//! The largest lengths the single-precision geometry holds, and the check that a shape's
//! triangles are still resolved where it stands.

use glam::Vec3;

/// Largest coordinate, size or radius accepted, m. Geometry is f32 (largest value 3.4e38):
/// a triangle's normal and area are the length of an edge cross product, whose squared
/// components overflow for edges above about 4e9 m (the normal becomes NaN and the surface
/// renders black), and the BVH builders' surface areas overflow at 1.8e19 m (obvhs then
/// panics). 1e8 m, a quarter of the way to the Moon, keeps every product of two lengths
/// below 1e16 m² with 40x to spare in length and is far beyond any scene brume renders.
pub const MAX_LENGTH: f32 = 1e8;

/// The distance between neighbouring f32 values at `p`'s largest coordinate, m: the finest
/// detail geometry there can hold.
pub fn resolution_at(p: Vec3) -> f32 {
    let m = p.abs().max_element();
    f32::from_bits(m.to_bits() + 1) - m
}

/// Why a point of a placed shape lies outside what the geometry holds (`None`: it is within).
/// A hair of slack lets the padded bounds of a sphere or disc of radius [`MAX_LENGTH`] pass.
pub fn out_of_range(p: Vec3) -> Option<String> {
    let m = p.abs().max_element();
    // NaN compares false: a non-finite coordinate is out of range too.
    let within = m <= MAX_LENGTH * (1.0 + 1e-4);
    (!within).then(|| {
        format!(
            "a coordinate of {m:e} m is beyond the {MAX_LENGTH:e} m that brume's \
             single-precision geometry holds (larger lengths overflow areas, normals and \
             bounding boxes)"
        )
    })
}

/// Why a shape whose triangles all lost their area once placed (a vertex of it at `p`) is
/// refused: its vertices round to the same f32 values there.
pub(crate) fn collapsed_at(p: Vec3) -> String {
    format!(
        "its triangles have no area once placed: at {:e} m from the origin single-precision \
         coordinates are {} m apart, coarser than the shape; move the scene nearer the origin",
        p.abs().max_element(),
        resolution_at(p)
    )
}
