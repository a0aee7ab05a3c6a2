//! What identifies a render: the film of passes `a..b` is only the film of passes `a..b` of *this*
//! render if the scene, the seed and every setting that changes how a pass is sampled are the
//! same. Checkpoints and parts carry a [`FilmId`]; resume and merge compare them and refuse a
//! mismatch, naming what differs.
//!
//! The film does not know the scene format (the scene depends on the film, not the reverse):
//! the caller passes its description as any `Serialize` value, and the keys that may differ
//! between the runs of one render are named here as dotted paths of that description.

use serde::{Deserialize, Serialize};
use serde_json::Value;

/// Dotted keys of the scene description that do not identify a render: the pass count and
/// seed (the seed is compared on its own), where outputs go, and the gather memory setting,
/// which is replaced by the budget it resolved to ([`Sampling::gather_budget`]).
pub const PER_RUN_KEYS: [&str; 4] = [
    "integrator.passes",
    "integrator.seed",
    "integrator.max_gather_bytes",
    "film.outputs",
];

/// How many differing keys a mismatch lists.
const LISTED: usize = 6;

/// Settings of a render that change its passes but are not in the scene description: they
/// depend on the machine or the program.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Sampling {
    /// Gather memory budget in bytes the passes were rendered with. A pass whose gather
    /// records exceed it is split into row tiles with their own light streams, so it decides
    /// the tiling and with it every pass.
    pub gather_budget: u64,
    /// Memory of the machine that rendered, in bytes (0 if unknown). Not compared: it only
    /// explains a budget that followed it.
    pub machine_memory: u64,
    /// The brume version that rendered (sampling code may change between versions).
    pub version: String,
}

/// What identifies the render a film belongs to.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FilmId {
    pub seed: u64,
    /// FNV-1a 64 of the canonical JSON of `description`: a quick test of "same scene".
    pub scene_hash: u64,
    /// The scene description without [`PER_RUN_KEYS`], as JSON (objects sorted by key).
    pub description: Value,
    pub sampling: Sampling,
}

#[derive(Debug, thiserror::Error)]
pub enum IdentityError {
    #[error("the scene description cannot be recorded: {0}")]
    Serialize(#[from] serde_json::Error),
}

/// Why a film is not of the render it is compared with: "ours" is the film compared, "theirs"
/// the reference (the request being made, or another part of a merge).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Mismatch {
    Seed {
        ours: u64,
        theirs: u64,
    },
    /// The scene descriptions differ at these keys.
    Settings(Vec<Difference>),
    GatherBudget {
        ours: u64,
        theirs: u64,
        ours_memory: u64,
        theirs_memory: u64,
    },
    Version {
        ours: String,
        theirs: String,
    },
}

/// One key whose values differ (JSON text; `absent` when one side lacks it).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Difference {
    pub key: String,
    pub ours: String,
    pub theirs: String,
}

impl Mismatch {
    /// The mismatch in words, naming the two films `ours` and `theirs` (such as file names).
    pub fn describe(&self, ours: &str, theirs: &str) -> String {
        match self {
            Mismatch::Seed { ours: a, theirs: b } => {
                format!("seed {a} in {ours}, {b} in {theirs}")
            }
            Mismatch::Settings(d) => {
                let mut parts: Vec<String> = d
                    .iter()
                    .take(LISTED)
                    .map(|d| format!("{} = {} in {ours}, {} in {theirs}", d.key, d.ours, d.theirs))
                    .collect();
                if d.len() > LISTED {
                    parts.push(format!("and {} more keys", d.len() - LISTED));
                }
                format!("another scene or other settings: {}", parts.join("; "))
            }
            Mismatch::GatherBudget {
                ours: a,
                theirs: b,
                ours_memory: ma,
                theirs_memory: mb,
            } => format!(
                "gather memory budget {a} bytes in {ours} (machine memory {ma} bytes), {b} bytes \
                 in {theirs} (machine memory {mb} bytes); the budget decides how passes are \
                 tiled: set the same integrator.max_gather_bytes for every run"
            ),
            Mismatch::Version { ours: a, theirs: b } => {
                format!("rendered by brume {a} in {ours}, brume {b} in {theirs}")
            }
        }
    }
}

impl std::fmt::Display for Mismatch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.describe("this film", "the other"))
    }
}

impl std::error::Error for Mismatch {}

impl FilmId {
    /// The identity of rendering `description` with `seed` and `sampling`.
    pub fn new(
        description: &impl Serialize,
        seed: u64,
        sampling: Sampling,
    ) -> Result<Self, IdentityError> {
        let mut value = serde_json::to_value(description)?;
        for key in PER_RUN_KEYS {
            remove_key(&mut value, key);
        }
        Ok(Self::from_parts(seed, value, sampling))
    }

    /// An identity from its recorded parts (as read from a film file).
    pub fn from_parts(seed: u64, description: Value, sampling: Sampling) -> Self {
        let scene_hash = hash(&description);
        Self {
            seed,
            scene_hash,
            description,
            sampling,
        }
    }

    /// One section of the description (such as the film's output settings), if present.
    pub fn section(&self, key: &str) -> Option<&Value> {
        self.description.get(key)
    }

    /// `Ok` when a film of `self` continues or completes a film of `reference` exactly.
    pub fn check(&self, reference: &FilmId) -> Result<(), Mismatch> {
        self.check_except(reference, &[])
    }

    /// [`FilmId::check`] with the dotted keys `ignored` left out of the descriptions'
    /// comparison: for keys the caller knows to leave this film's passes unchanged (such as a
    /// radius schedule that only differs after the passes in question).
    pub fn check_except(&self, reference: &FilmId, ignored: &[&str]) -> Result<(), Mismatch> {
        if self.seed != reference.seed {
            return Err(Mismatch::Seed {
                ours: self.seed,
                theirs: reference.seed,
            });
        }
        if self.scene_hash != reference.scene_hash || self.description != reference.description {
            let mut found = Vec::new();
            differences(&self.description, &reference.description, "", &mut found);
            found.retain(|d| !ignored.contains(&d.key.as_str()));
            if !found.is_empty() {
                return Err(Mismatch::Settings(found));
            }
        }
        let (ours, theirs) = (&self.sampling, &reference.sampling);
        if ours.gather_budget != theirs.gather_budget {
            return Err(Mismatch::GatherBudget {
                ours: ours.gather_budget,
                theirs: theirs.gather_budget,
                ours_memory: ours.machine_memory,
                theirs_memory: theirs.machine_memory,
            });
        }
        if ours.version != theirs.version {
            return Err(Mismatch::Version {
                ours: ours.version.clone(),
                theirs: theirs.version.clone(),
            });
        }
        Ok(())
    }
}

/// FNV-1a 64 of the canonical JSON text (serde_json's maps are sorted by key).
pub fn hash(v: &Value) -> u64 {
    let mut h = Fnv::default();
    h.update(v.to_string().as_bytes());
    h.0
}

/// FNV-1a 64: a small, stable hash (the same on every machine and build), used for the scene
/// hash and the film file's checksum.
#[derive(Clone, Copy, Debug)]
pub struct Fnv(pub u64);

impl Default for Fnv {
    fn default() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv {
    pub fn update(&mut self, bytes: &[u8]) {
        for b in bytes {
            self.0 ^= *b as u64;
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
}

fn remove_key(v: &mut Value, dotted: &str) {
    let mut cur = v;
    let mut keys = dotted.split('.').peekable();
    while let Some(k) = keys.next() {
        let Value::Object(map) = cur else { return };
        if keys.peek().is_none() {
            map.remove(k);
            return;
        }
        match map.get_mut(k) {
            Some(next) => cur = next,
            None => return,
        }
    }
}

/// Collects the dotted keys (`media.fog.g`, `shapes.1.radius`) whose values differ.
fn differences(a: &Value, b: &Value, at: &str, out: &mut Vec<Difference>) {
    let child = |at: &str, k: &str| {
        if at.is_empty() {
            k.to_string()
        } else {
            format!("{at}.{k}")
        }
    };
    match (a, b) {
        (Value::Object(x), Value::Object(y)) => {
            let keys: std::collections::BTreeSet<&String> = x.keys().chain(y.keys()).collect();
            for k in keys {
                let sub = child(at, k);
                match (x.get(k), y.get(k)) {
                    (Some(p), Some(q)) => differences(p, q, &sub, out),
                    (p, q) => out.push(difference(sub, p, q)),
                }
            }
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => {
            for (i, (p, q)) in x.iter().zip(y).enumerate() {
                differences(p, q, &child(at, &i.to_string()), out);
            }
        }
        _ if a != b => out.push(difference(at.to_string(), Some(a), Some(b))),
        _ => {}
    }
}

fn difference(key: String, a: Option<&Value>, b: Option<&Value>) -> Difference {
    let text = |v: Option<&Value>| match v {
        Some(Value::Array(items)) => format!("[{} entries]", items.len()),
        // Scene values are mostly f32, recorded as f64: show the value as it was written.
        Some(Value::Number(n)) => match n.as_f64() {
            Some(f) if n.is_f64() && (f as f32) as f64 == f => (f as f32).to_string(),
            _ => n.to_string(),
        },
        Some(v) => v.to_string(),
        None => "absent".to_string(),
    };
    Difference {
        key: if key.is_empty() {
            "(scene)".into()
        } else {
            key
        },
        ours: text(a),
        theirs: text(b),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn sampling(budget: u64, memory: u64) -> Sampling {
        Sampling {
            gather_budget: budget,
            machine_memory: memory,
            version: "1.0".into(),
        }
    }

    fn desc() -> Value {
        json!({
            "integrator": {"passes": 16, "seed": 3, "q": 0.5, "max_gather_bytes": 0},
            "film": {"bins": 32, "outputs": ["a.exr"]},
            "shapes": [{"radius": 1.0}, {"radius": 2.0}],
        })
    }

    #[test]
    fn per_run_keys_do_not_change_the_identity() {
        let a = FilmId::new(&desc(), 7, sampling(100, 8)).unwrap();
        let mut d = desc();
        d["integrator"]["passes"] = json!(99);
        d["integrator"]["seed"] = json!(4);
        d["integrator"]["max_gather_bytes"] = json!(100);
        d["film"]["outputs"] = json!(["b.png"]);
        // Another machine's memory alone does not matter: the budget it led to does.
        let b = FilmId::new(&d, 7, sampling(100, 16)).unwrap();
        assert_eq!(b.check(&a), Ok(()));
        assert!(a.description["integrator"].get("passes").is_none());
    }

    #[test]
    fn each_difference_is_named() {
        let a = FilmId::new(&desc(), 7, sampling(100, 8)).unwrap();
        let mut d = desc();
        d["integrator"]["q"] = json!(0.25);
        d["shapes"][1]["radius"] = json!(3.0);
        let b = FilmId::new(&d, 7, sampling(100, 8)).unwrap();
        let err = b.check(&a).unwrap_err();
        let text = err.to_string();
        assert!(
            text.contains("integrator.q = 0.25 in this film, 0.5 in the other"),
            "{text}"
        );
        assert!(text.contains("shapes.1.radius = 3 in this film"), "{text}");
        let c = FilmId::new(&desc(), 8, sampling(100, 8)).unwrap();
        assert_eq!(c.check(&a), Err(Mismatch::Seed { ours: 8, theirs: 7 }));
        let e = FilmId::new(&desc(), 7, sampling(50, 4)).unwrap();
        let text = e.check(&a).unwrap_err().to_string();
        assert!(text.contains("gather memory budget 50 bytes"), "{text}");
        let mut v = sampling(100, 8);
        v.version = "2.0".into();
        let f = FilmId::new(&desc(), 7, v).unwrap();
        assert!(matches!(f.check(&a), Err(Mismatch::Version { .. })));
    }

    /// Ignored keys leave the others compared, whether they differ in value or are absent on
    /// one side.
    #[test]
    fn ignored_keys_are_left_out_and_only_they() {
        let a = FilmId::new(&desc(), 7, sampling(100, 8)).unwrap();
        let mut d = desc();
        d["integrator"]["schedule"] = json!("fixed");
        d["integrator"]["q"] = json!(0.25);
        let b = FilmId::new(&d, 7, sampling(100, 8)).unwrap();
        let only_q = b.check_except(&a, &["integrator.schedule"]).unwrap_err();
        assert_eq!(
            only_q,
            Mismatch::Settings(vec![Difference {
                key: "integrator.q".into(),
                ours: "0.25".into(),
                theirs: "0.5".into(),
            }])
        );
        d["integrator"]["q"] = json!(0.5);
        let c = FilmId::new(&d, 7, sampling(100, 8)).unwrap();
        assert_eq!(c.check_except(&a, &["integrator.schedule"]), Ok(()));
        assert!(c.check(&a).is_err());
        // The checks after the description's still apply.
        let e = FilmId::new(&d, 7, sampling(50, 8)).unwrap();
        assert!(matches!(
            e.check_except(&a, &["integrator.schedule"]),
            Err(Mismatch::GatherBudget { .. })
        ));
    }
}
