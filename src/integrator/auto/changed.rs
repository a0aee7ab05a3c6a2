//! A choice as films record it, and a resumed film whose recorded choice is not the one the
//! pilots make now.

use super::PassConfig;

/// A configuration as a choice reports it (`Film::auto_choice` reads it back).
pub fn settings_of(c: &PassConfig) -> String {
    let radius = if c.indirect_scale == 1.0 {
        // As films recorded their choices before the radius was one of them.
        String::new()
    } else {
        format!(", radius_indirect = {} x radius", c.indirect_scale)
    };
    format!(
        "q = {:?}, forward_rays = {}, camera_samples = {}{radius}",
        c.q, c.forward_rays, c.camera_samples
    )
}

/// The film's passes were rendered with the automatic settings `film` (its recorded choice,
/// `Film::auto_choice`), and this brume's pilot passes choose `now`: a brume whose pilots
/// sample differently began it. Its passes are valid, but added to them this brume's would
/// make an image of two configurations that names one.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error(
    "the film's passes were rendered with the automatic settings {film}, but this brume's pilot \
     passes choose {now} (another brume, whose pilots choose differently, began the film): \
     resuming would mix two configurations in one image; finish the film with the brume that \
     began it, or render it anew"
)]
pub struct ChoiceChanged {
    pub film: String,
    pub now: String,
}
