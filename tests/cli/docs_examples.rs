//! Every `brume` command in README.md and docs/*.md runs against the built binary.
//!
//! Commands are found in shell code blocks, indented blocks and inline code (`brume SUB ...`,
//! `target/release/brume SUB ...`, `cargo run --release -- SUB ...`, also inside quotes as
//! hyperfine takes them), then shrunk to run in seconds (rules in `shrink`), with every file
//! they write redirected into a temporary folder. The commands of one document run in order in
//! one folder, so a checkpoint written by one example is there for the next to resume.
//!
//! A command is skipped only by one of the rules in `skip_reason`, and the test prints each
//! skipped command with its rule.

use std::path::{Path, PathBuf};
use std::process::Command;

const SUBCOMMANDS: [&str; 6] = ["render", "merge", "info", "spectrum", "study", "probe"];

/// Words the documents use as placeholders for the reader's own values.
const PLACEHOLDERS: [&str; 18] = [
    "SCENE",
    "FILE",
    "NAME",
    "OUT",
    "PARTS",
    "DIR",
    "N",
    "K",
    "I",
    "C",
    "L",
    "T",
    "SECONDS",
    "KEY",
    "VALUE",
    "V1",
    "REF.bin",
    "IMAGE.exr",
];

/// Shell words that end one command (and maybe start another).
const SEPARATORS: [&str; 5] = ["&&", "||", "|", ">", "2>"];

/// Code blocks whose language is not a shell's hold configuration, not commands.
const NOT_SHELL: [&str; 3] = ["yaml", "toml", "json"];

struct Example {
    line: usize,
    words: Vec<String>,
}

fn docs() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = vec![root.join("README.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root.join("docs"))
        .expect("docs/")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "md"))
        .collect();
    docs.sort();
    files.extend(docs);
    files
}

/// The commands of a document, with the line each starts on.
fn extract(text: &str) -> Vec<Example> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    let mut fence: Option<String> = None;
    let mut i = 0;
    while i < lines.len() {
        let line = lines[i];
        if let Some(lang) = line.trim_start().strip_prefix("```") {
            fence = match fence {
                Some(_) => None,
                None => Some(lang.trim().to_string()),
            };
            i += 1;
            continue;
        }
        if fence.as_deref().is_some_and(|l| NOT_SHELL.contains(&l)) {
            i += 1;
            continue;
        }
        // A command may continue over lines: with `\` in shell, inside an open inline span.
        let mut joined = line.to_string();
        let mut j = i;
        while (joined.trim_end().ends_with('\\') || joined.matches('`').count() % 2 == 1)
            && j + 1 < lines.len()
            && !lines[j + 1].trim_start().starts_with("```")
        {
            joined = format!(
                "{} {}",
                joined.trim_end().trim_end_matches('\\'),
                lines[j + 1]
            );
            j += 1;
        }
        for words in commands_in(&joined) {
            out.push(Example { line: i + 1, words });
        }
        i = j + 1;
    }
    out
}

/// Commands in one (joined) line: from the program to the end of the code span, quote or line.
fn commands_in(line: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    for start in ["cargo run --release -- ", "target/release/brume ", "brume "] {
        for (at, _) in line.match_indices(start) {
            let before = line[..at].chars().next_back();
            if before.is_some_and(|c| c.is_alphanumeric() || c == '/' || c == '-' || c == '.') {
                continue; // part of a longer word or path (e.g. `--brume target/release/brume`)
            }
            if start == "brume " && line[..at].ends_with("release/") {
                continue;
            }
            let rest = &line[at + start.len()..];
            let end = match before {
                Some('`') => rest.find('`'),
                Some('\'') => rest.find('\''),
                _ => rest.find('`'),
            };
            let text = &rest[..end.unwrap_or(rest.len())];
            let Some(mut words) = shlex::split(text) else {
                continue;
            };
            // The command ends where the shell starts another (`; perf report ...`).
            if let Some(end) = words
                .iter()
                .position(|w| w.ends_with(';') || SEPARATORS.contains(&w.as_str()))
            {
                let last = words[end].trim_end_matches(';').to_string();
                words.truncate(end);
                if !last.is_empty() && !SEPARATORS.contains(&last.as_str()) {
                    words.push(last);
                }
            }
            if words
                .first()
                .is_some_and(|w| SUBCOMMANDS.contains(&w.as_str()))
            {
                out.push(words);
            }
        }
    }
    out
}

/// Why a command cannot run on its own, if it cannot.
fn skip_reason(words: &[String]) -> Option<&'static str> {
    // `brume render` in prose names the subcommand; it is not an example.
    if words.len() == 1 {
        return Some("a subcommand named in prose");
    }
    let marks = ["[", "]", "|", "...", "<", ">", "$"];
    if words.iter().any(|w| marks.iter().any(|m| w.contains(m))) {
        return Some("a synopsis or shell variables ([..], |, ..., <..>, $VAR)");
    }
    let is_placeholder = |w: &str| {
        w.split(['=', ':', ','])
            .flat_map(|p| p.split(".."))
            .any(|p| PLACEHOLDERS.contains(&p))
    };
    if words.iter().any(|w| is_placeholder(w)) {
        return Some("a placeholder for the reader's own value (SCENE, FILE, N, ...)");
    }
    None
}

/// Options whose value is a file the command writes or reads from an earlier example.
const FILE_OPTIONS: [&str; 5] = ["-o", "--output", "--checkpoint", "--resume", "--reference"];
/// Options with a pass count, a time or a run count, shrunk to run fast.
const SMALL: [&str; 3] = [
    "camera.width=16",
    "camera.height=12",
    "integrator.forward_rays=2000",
];

/// The file a documented path is written to in the test's folder: the same relative path under
/// it (absolute paths too), so that a path used by two examples is the same file, and a file
/// written into a folder (`-o DIR` of a study) is found under that folder. Folders are made.
fn redirect(p: &str, out: &Path) -> String {
    let rel = p.trim_start_matches("./").trim_start_matches('/');
    let path = out.join(rel);
    if let Some(dir) = path.parent() {
        let _ = std::fs::create_dir_all(dir);
    }
    path.to_string_lossy().into_owned()
}

/// The command made small: 1 pass instead of N or a time, tiny images, runs of a twentieth of
/// a second for studies, pass ranges divided by `range_unit` (so adjacent parts stay adjacent),
/// the generic `scene.toml` of the docs played by scenes/fog-cube.toml, and every file written
/// or read by name redirected into `out`.
fn shrink(words: &[String], out: &Path, range_unit: u64) -> Vec<String> {
    let sub = words[0].as_str();
    let mut args = vec![words[0].clone()];
    let mut it = words[1..].iter().peekable();
    while let Some(w) = it.next() {
        let value = |it: &mut std::iter::Peekable<std::slice::Iter<String>>| {
            it.next().cloned().unwrap_or_default()
        };
        match w.as_str() {
            "--passes" => {
                value(&mut it);
                args.extend(["--passes".into(), "1".into()]);
            }
            "--time" if sub == "render" => {
                value(&mut it);
                args.extend(["--passes".into(), "1".into()]);
            }
            "--time" | "--reference-time" => {
                value(&mut it);
                args.extend([w.clone(), "0.05".into()]);
            }
            "--runs" => {
                value(&mut it);
                args.extend(["--runs".into(), "1".into()]);
            }
            "--pass-range" => {
                let v = value(&mut it);
                let (a, b) = v.split_once("..").unwrap_or(("0", "1"));
                let scale = |x: &str| (x.parse::<u64>().unwrap_or(0) / range_unit).to_string();
                args.extend(["--pass-range".into(), format!("{}..{}", scale(a), scale(b))]);
            }
            o if FILE_OPTIONS.contains(&o) => {
                let v = value(&mut it);
                args.extend([w.clone(), redirect(&v, out)]);
            }
            "scene.toml" => args.push(in_repository("scenes/fog-cube.toml")),
            image if sub == "probe" && image.ends_with(".exr") => args.push(redirect(image, out)),
            part if sub == "merge" && part.ends_with(".brume") => {
                args.extend(glob(&redirect(part, out)));
            }
            // The repository's own files (scenes/...), as the command runs in `out`.
            file if !file.starts_with('-') && repository().join(file).exists() => {
                args.push(in_repository(file))
            }
            _ => args.push(w.clone()),
        }
    }
    if matches!(sub, "render" | "study" | "info") {
        for s in SMALL {
            args.extend(["--set".into(), s.into()]);
        }
    }
    args
}

fn repository() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The absolute path of a file of the repository.
fn in_repository(rel: &str) -> String {
    repository().join(rel).to_string_lossy().into_owned()
}

/// The names in a folder (the repository's root and scenes/, which examples must not write to).
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("readable folder")
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// Expands one `*` in the file name (the docs' `part-*.brume`), as the shell would.
fn glob(pattern: &str) -> Vec<String> {
    let p = Path::new(pattern);
    let name = p
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let Some((pre, post)) = name.split_once('*') else {
        return vec![pattern.to_string()];
    };
    let dir = p.parent().unwrap_or(Path::new("."));
    let mut found: Vec<String> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(pre) && n.ends_with(post) && n.len() >= pre.len() + post.len())
        .map(|n| dir.join(n).to_string_lossy().into_owned())
        .collect();
    found.sort();
    found
}

/// The largest unit dividing every pass-range bound of a document.
fn range_unit(examples: &[Example]) -> u64 {
    fn gcd(a: u64, b: u64) -> u64 {
        if b == 0 { a } else { gcd(b, a % b) }
    }
    let bounds = examples.iter().flat_map(|e| {
        e.words
            .windows(2)
            .filter(|w| w[0] == "--pass-range")
            .flat_map(|w| {
                w[1].split("..")
                    .filter_map(|x| x.parse::<u64>().ok())
                    .collect::<Vec<_>>()
            })
            .collect::<Vec<_>>()
    });
    bounds.fold(0, gcd).max(1)
}

#[test]
fn every_documented_command_runs() {
    let root = repository();
    let before = [listing(root), listing(&root.join("scenes"))];
    let (mut ran, mut skipped, mut failed) = (0, Vec::new(), Vec::new());
    for doc in docs() {
        let text = std::fs::read_to_string(&doc).expect("readable doc");
        let name = doc.strip_prefix(root).unwrap_or(&doc).display().to_string();
        let examples = extract(&text);
        let unit = range_unit(&examples);
        let tmp = tempfile::tempdir().expect("tempdir");
        for e in &examples {
            let shown = format!("{name}:{}: brume {}", e.line, e.words.join(" "));
            if let Some(why) = skip_reason(&e.words) {
                skipped.push(format!("{shown}\n    skipped: {why}"));
                continue;
            }
            let args = shrink(&e.words, tmp.path(), unit);
            // A merge of parts that only skipped examples (with $VAR) would make.
            if args[0] == "merge" && !args.iter().any(|a| a.ends_with(".brume")) {
                let why = "its parts come from examples skipped above";
                skipped.push(format!("{shown}\n    skipped: {why}"));
                continue;
            }
            // In the test's folder: a command that writes a file it is not told to (a
            // render's default `fog-cube.exr`) writes it there, not into the repository.
            let out = Command::new(env!("CARGO_BIN_EXE_brume"))
                .current_dir(tmp.path())
                .args(&args)
                .output()
                .expect("brume runs");
            ran += 1;
            if !out.status.success() {
                let err = String::from_utf8_lossy(&out.stderr);
                failed.push(format!("{shown}\n    ran: {}\n    {err}", args.join(" ")));
            }
        }
    }
    eprintln!(
        "{} documented commands skipped:\n{}",
        skipped.len(),
        skipped.join("\n")
    );
    assert!(
        failed.is_empty(),
        "documented commands fail:\n{}",
        failed.join("\n")
    );
    // README's quick start, its image commands, the distributed and study examples at least.
    assert!(ran >= 12, "only {ran} documented commands found and run");
    let after = [listing(root), listing(&root.join("scenes"))];
    for (b, a) in before.iter().zip(&after) {
        let new: Vec<&String> = a.iter().filter(|n| !b.contains(n)).collect();
        assert!(
            new.is_empty(),
            "documented commands wrote {new:?} into the repository"
        );
    }
}

#[test]
fn extraction_finds_commands_in_every_form() {
    let doc = "Run `brume render` or:\n\n```sh\ncargo run --release -- render a.toml \\\n  \
               --passes 3 -o x.png; ls\n```\n\n    brume merge p-*.brume -o m.exr\n\n\
               `hyperfine 'target/release/brume info s.toml --quiet'`\n\
               `--brume target/release/brume --ref-seconds 5`\n```yaml\nbrume render /s.toml\n```\n";
    let found: Vec<String> = extract(doc).iter().map(|e| e.words.join(" ")).collect();
    assert_eq!(
        found,
        [
            "render",
            "render a.toml --passes 3 -o x.png",
            "merge p-*.brume -o m.exr",
            "info s.toml --quiet",
        ]
    );
    let words = |s: &str| s.split(' ').map(String::from).collect::<Vec<_>>();
    assert!(skip_reason(&words("render SCENE -o out.exr")).is_some());
    assert!(skip_reason(&words("spectrum colorchecker:K --illuminant A")).is_some());
    assert!(skip_reason(&words("spectrum D65 --illuminant A")).is_none());
}
