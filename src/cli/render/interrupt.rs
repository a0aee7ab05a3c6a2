//! Ctrl-C and SIGTERM. During setup (loading, building the scene: Lorenz-Mie droplets or a large
//! mesh can take minutes) nothing has been rendered, so brume exits at once with 130. While
//! rendering, the first stops the pass in flight (the engine never adds a partial pass to the
//! film), then brume saves the completed passes and exits 130. While the outputs are written
//! (a large spectral EXR takes a while), the first lets the writing finish and brume then exits
//! 130. In both a second aborts at once with 130: every output is written to a temporary name
//! and renamed into place, so an abort leaves each file either complete or as it was.
//!
//! A signal that brume was started with ignored stays ignored, as in any program that does not
//! catch it: `nohup brume render ...` ignores SIGHUP, so a long render started over ssh outlives
//! the terminal, and a script's background job (`brume render ... &`) ignores SIGINT, so a
//! Ctrl-C meant for the script does not stop it. (The handler catches SIGINT, SIGTERM and
//! SIGHUP alike: before this, nohup's ignored SIGHUP stopped the render.)

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU8, AtomicUsize, Ordering};

use nix::sys::signal::{SigHandler, Signal, signal};

/// Exit status of an interrupted render (the shell convention for SIGINT).
pub const INTERRUPTED: u8 = 130;

/// What the process is doing when a signal comes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Phase {
    Setup = 0,
    Rendering = 1,
    Writing = 2,
}

impl Phase {
    fn from_u8(v: u8) -> Self {
        match v {
            0 => Phase::Setup,
            1 => Phase::Rendering,
            // Only the three phases are ever stored.
            _ => Phase::Writing,
        }
    }
}

/// What the handler does with the `count`-th signal (0-based) in `phase`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Action {
    /// Exit with 130 now, printing the message.
    Exit(&'static str),
    /// Raise the stop flag and go on, printing the message (unless quiet).
    Stop(&'static str),
}

fn action(phase: Phase, count: usize) -> Action {
    match (phase, count) {
        // Outputs are written only after rendering (at most the empty file that checked a
        // folder is writable can be left, and the next run on that output removes it).
        (Phase::Setup, _) => {
            Action::Exit("interrupted during setup, before any pass: nothing written")
        }
        (Phase::Rendering, 0) => Action::Stop(
            "interrupt: stopping the pass in flight, then saving the completed passes \
             (interrupt again to abort without saving)",
        ),
        (Phase::Writing, 0) => Action::Stop(
            "interrupt: finishing the outputs being written, then exiting (interrupt again to \
             abort: a file not yet written keeps its previous content)",
        ),
        (Phase::Rendering | Phase::Writing, _) => Action::Exit(
            "aborted (each output is either complete or as it was: files are written to a \
             temporary name and renamed into place)",
        ),
    }
}

/// The flags the handler shares with the render.
pub struct Interrupt {
    /// Set by the first interrupt while rendering or writing: the engine stops the pass in
    /// flight, and the command exits 130 once its files are written.
    pub stop: Arc<AtomicBool>,
    phase: Arc<AtomicU8>,
}

impl Interrupt {
    /// From now on an interrupt stops the render and saves its passes instead of exiting.
    pub fn rendering_starts(&self) {
        self.phase.store(Phase::Rendering as u8, Ordering::SeqCst);
    }

    /// From now on an interrupt lets the outputs being written finish (a second aborts).
    pub fn writing_starts(&self) {
        self.phase.store(Phase::Writing as u8, Ordering::SeqCst);
    }

    /// Whether an interrupt came since rendering started.
    pub fn interrupted(&self) -> bool {
        self.stop.load(Ordering::SeqCst)
    }
}

/// Installs the handler. Called first thing, so that a signal during scene loading and building
/// is caught as well.
pub fn install(quiet: bool) -> Interrupt {
    let ignored = ignored_at_start();
    let stop = Arc::new(AtomicBool::new(false));
    let phase = Arc::new(AtomicU8::new(Phase::Setup as u8));
    let count = AtomicUsize::new(0);
    let (flag, shared_phase) = (stop.clone(), phase.clone());
    let result = ctrlc::set_handler(move || {
        let now = Phase::from_u8(shared_phase.load(Ordering::SeqCst));
        let n = if now == Phase::Setup {
            0
        } else {
            count.fetch_add(1, Ordering::SeqCst)
        };
        match action(now, n) {
            Action::Exit(message) => {
                eprintln!("\nbrume: {message}");
                std::process::exit(INTERRUPTED as i32);
            }
            Action::Stop(message) => {
                flag.store(true, Ordering::SeqCst);
                if !quiet {
                    eprintln!("\nbrume: {message}");
                }
            }
        }
    });
    if let Err(e) = result {
        eprintln!("brume: warning: cannot catch interrupts ({e}); Ctrl-C will lose the render");
    }
    for s in ignored {
        ignore(s);
    }
    Interrupt { stop, phase }
}

/// The signals the handler catches (`ctrlc`'s `termination` set).
const CAUGHT: [Signal; 3] = [Signal::SIGINT, Signal::SIGTERM, Signal::SIGHUP];

/// Those of [`CAUGHT`] that this process was started with ignored (the module's comment). Each
/// is set to ignored and its previous disposition put back at once: that is how a signal's
/// disposition is read.
fn ignored_at_start() -> Vec<Signal> {
    CAUGHT
        .into_iter()
        .filter(|&s| match ignore(s) {
            Some(SigHandler::SigIgn) => true,
            Some(previous) => {
                // SAFETY: `previous` is the disposition this process had a moment ago (the
                // default, at start); no handler of brume's runs between the two calls.
                let _ = unsafe { signal(s, previous) };
                false
            }
            None => false,
        })
        .collect()
}

/// Ignores `s`; its previous disposition, or None if the system refused.
fn ignore(s: Signal) -> Option<SigHandler> {
    // SAFETY: SIG_IGN installs no handler function, so nothing can run in a signal context.
    unsafe { signal(s, SigHandler::SigIgn) }.ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A second interrupt exits while rendering and while writing, whatever phase the first
    /// came in; the first never exits once rendering started.
    #[test]
    fn a_second_interrupt_always_exits() {
        for phase in [Phase::Rendering, Phase::Writing] {
            assert!(matches!(action(phase, 0), Action::Stop(_)), "{phase:?}");
            for n in 1..4 {
                assert!(matches!(action(phase, n), Action::Exit(_)), "{phase:?} {n}");
            }
        }
        assert!(matches!(action(Phase::Setup, 0), Action::Exit(_)));
        for p in [Phase::Setup, Phase::Rendering, Phase::Writing] {
            assert_eq!(Phase::from_u8(p as u8), p);
        }
    }
}
