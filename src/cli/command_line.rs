//! The command line as the user typed it, rewritten for the hints brume prints ("continue with
//! ..."): every option the user gave (`--set`, `-o`, `--seed`, ...) is kept, so following the
//! hint renders the same scene with the same settings.

use std::ffi::OsString;

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CommandLine {
    args: Vec<OsString>,
}

impl CommandLine {
    /// This process's command line.
    pub fn current() -> Self {
        Self {
            args: std::env::args_os().collect(),
        }
    }

    #[cfg(test)]
    pub fn from(args: &[&str]) -> Self {
        Self {
            args: args.iter().map(OsString::from).collect(),
        }
    }

    /// The command line without the options `drop` (each given as `--opt VALUE` or
    /// `--opt=VALUE`), followed by `add` (option, value) pairs.
    pub fn replacing(&self, drop: &[&str], add: &[(&str, String)]) -> Self {
        let mut args = Vec::with_capacity(self.args.len() + 2 * add.len());
        let mut it = self.args.iter();
        while let Some(a) = it.next() {
            let text = a.to_string_lossy();
            if drop.contains(&text.as_ref()) {
                it.next();
                continue;
            }
            let joined = text
                .split_once('=')
                .is_some_and(|(k, _)| k.starts_with("--") && drop.contains(&k));
            if !joined {
                args.push(a.clone());
            }
        }
        for (opt, value) in add {
            args.push(OsString::from(opt));
            args.push(OsString::from(value));
        }
        Self { args }
    }

    /// The command for a POSIX shell, each word quoted as needed.
    pub fn shell(&self) -> String {
        self.args
            .iter()
            .map(|a| {
                let s = a.to_string_lossy();
                shlex::try_quote(&s)
                    .map(|q| q.into_owned())
                    .unwrap_or_else(|_| format!("{s:?}"))
            })
            .collect::<Vec<_>>()
            .join(" ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeps_every_other_option_and_quotes() {
        let c = CommandLine::from(&[
            "brume",
            "render",
            "my scene.toml",
            "--set",
            "media.fog.g=0.3",
            "--passes=40",
            "--resume",
            "old.brume",
            "-o",
            "a.exr",
        ]);
        let r = c.replacing(
            &["--passes", "--resume"],
            &[
                ("--pass-range", "15..40".into()),
                ("--resume", "c.brume".into()),
            ],
        );
        assert_eq!(
            r.shell(),
            "brume render 'my scene.toml' --set 'media.fog.g=0.3' -o a.exr --pass-range 15..40 \
             --resume c.brume"
        );
    }
}
