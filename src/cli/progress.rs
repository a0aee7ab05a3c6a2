//! Progress reporting: a bar on a terminal, plain periodic lines otherwise (logs, CI).

use std::io::IsTerminal;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};

pub enum Progress {
    Bar(ProgressBar),
    Lines {
        label: String,
        total: u64,
        last: Instant,
        start: Instant,
    },
    Silent,
}

const LINE_INTERVAL: Duration = Duration::from_secs(5);

impl Progress {
    pub fn new(label: &str, total: u64, quiet: bool) -> Self {
        if quiet {
            return Progress::Silent;
        }
        if std::io::stderr().is_terminal() {
            let bar = ProgressBar::new(total);
            let style = ProgressStyle::with_template(
                "{prefix} [{elapsed_precise}] {wide_bar} {pos}/{len} {msg} (eta {eta})",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar());
            bar.set_style(style);
            bar.set_prefix(label.to_string());
            Progress::Bar(bar)
        } else {
            // A first line at once: a log then shows when the work (after setup) began.
            eprintln!("{label}: 0/{total} after 0.0 s");
            let now = Instant::now();
            Progress::Lines {
                label: label.to_string(),
                total,
                last: now,
                start: now,
            }
        }
    }

    pub fn set(&mut self, done: u64, message: &str) {
        match self {
            Progress::Bar(b) => {
                b.set_position(done);
                b.set_message(message.to_string());
            }
            Progress::Lines {
                label,
                total,
                last,
                start,
            } => {
                if last.elapsed() >= LINE_INTERVAL || done == *total {
                    *last = Instant::now();
                    eprintln!(
                        "{label}: {done}/{total} after {:.1} s {message}",
                        start.elapsed().as_secs_f64()
                    );
                }
            }
            Progress::Silent => {}
        }
    }

    pub fn finish(&mut self) {
        if let Progress::Bar(b) = self {
            b.finish_and_clear();
        }
    }
}
