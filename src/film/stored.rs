//! The JSON texts of a film file (`checkpoint`): the render's identity, and what the film keeps
//! beside its sums. Both are read leniently in the direction that lets files cross versions: a
//! key a newer brume adds is ignored by an older one, and one an older brume did not write reads
//! as its default.

use serde::{Deserialize, Serialize};

use super::identity::Sampling;
use super::{Film, FilmExtras};

/// The identity as stored: JSON, readable with any tool.
#[derive(Serialize, Deserialize)]
pub(super) struct StoredIdentity {
    pub description: serde_json::Value,
    pub sampling: Sampling,
}

/// The extras text as written: the film's sensors and light layers, and the automatic
/// settings' choice when the render made one (files written before films kept it lack the
/// key).
#[derive(Serialize)]
struct ExtrasOut<'a> {
    #[serde(flatten)]
    extras: &'a FilmExtras,
    #[serde(skip_serializing_if = "<[String]>::is_empty")]
    auto_settings: &'a [String],
}

#[derive(Deserialize)]
struct ExtrasIn {
    #[serde(flatten)]
    extras: FilmExtras,
    #[serde(default)]
    auto_settings: Vec<String>,
}

/// The extras text of `film`.
pub(super) fn extras_json(film: &Film) -> serde_json::Result<Vec<u8>> {
    serde_json::to_vec(&ExtrasOut {
        extras: &film.extras,
        auto_settings: &film.auto_settings,
    })
}

/// The extras and the automatic settings' choice from an extras text.
pub(super) fn read_extras(text: &[u8]) -> serde_json::Result<(FilmExtras, Vec<String>)> {
    let e: ExtrasIn = serde_json::from_slice(text)?;
    Ok((e.extras, e.auto_settings))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::SpectralGrid;

    /// The choice survives the round trip; a text without it (a film written before films
    /// kept it) reads as no choice; the extras text an older brume reads is unchanged but for
    /// the added key.
    #[test]
    fn the_choice_round_trips_and_older_texts_read() {
        let mut film = Film::new(2, 2, SpectralGrid::new(4, 380.0, 780.0));
        film.extras.light_layers = vec!["light0.spot".into()];
        let plain = extras_json(&film).unwrap();
        assert_eq!(plain, serde_json::to_vec(&film.extras).unwrap());
        assert_eq!(read_extras(&plain).unwrap(), (film.extras.clone(), vec![]));
        film.auto_settings = vec!["q = [1.0]".into(), "camera_samples = 4".into()];
        let text = extras_json(&film).unwrap();
        let (extras, auto) = read_extras(&text).unwrap();
        assert_eq!(
            (extras, auto),
            (film.extras.clone(), film.auto_settings.clone())
        );
        // What an older brume does with the new text: FilmExtras alone, the key ignored.
        let old: FilmExtras = serde_json::from_slice(&text).unwrap();
        assert_eq!(old, film.extras);
    }
}
