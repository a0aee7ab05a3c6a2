//! `"auto"` settings chosen from measurements of the first passes (issue 18).

/// The smallest q an automatic choice takes: about 33 spheres per camera segment in thick fog.
pub const Q_MIN: f32 = 0.03;
