//! The study's variants: the cartesian product of `--vary KEY=V1,V2,...` lists.

use super::StudyError;

/// One `--vary`: a scene key and the values it takes.
#[derive(Clone, Debug, PartialEq)]
pub struct Vary {
    pub key: String,
    pub values: Vec<String>,
}

pub fn parse_vary(text: &str) -> Result<Vary, StudyError> {
    let bad = || StudyError::Vary(text.to_string());
    let (key, list) = text.split_once('=').ok_or_else(bad)?;
    let key = key.trim();
    let values: Vec<String> = list
        .split(',')
        .map(|v| v.trim().to_string())
        .filter(|v| !v.is_empty())
        .collect();
    if key.is_empty() || values.is_empty() {
        return Err(bad());
    }
    Ok(Vary {
        key: key.to_string(),
        values,
    })
}

/// One combination: its `--set` overrides (KEY=VALUE) and a label like `q=0.3 volume=cylinder`.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Variant {
    pub label: String,
    pub sets: Vec<String>,
    /// (key, value) per varied key, in `--vary` order.
    pub values: Vec<(String, String)>,
}

/// The cartesian product, the first `--vary` varying slowest.
pub fn expand(varies: &[Vary]) -> Vec<Variant> {
    let mut out = vec![Variant {
        label: String::new(),
        sets: Vec::new(),
        values: Vec::new(),
    }];
    for v in varies {
        let short = v.key.rsplit('.').next().unwrap_or(&v.key).to_string();
        out = out
            .into_iter()
            .flat_map(|base| {
                let short = &short;
                v.values.iter().map(move |val| {
                    let mut n = base.clone();
                    n.sets.push(format!("{}={}", v.key, val));
                    n.values.push((v.key.clone(), val.clone()));
                    if !n.label.is_empty() {
                        n.label.push(' ');
                    }
                    n.label.push_str(&format!("{short}={val}"));
                    n
                })
            })
            .collect();
    }
    if out.len() == 1 && out[0].label.is_empty() {
        out[0].label = "base".into();
    }
    out
}
