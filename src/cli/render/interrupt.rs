//! Ctrl-C and SIGTERM. During setup (loading, building the scene: Lorenz-Mie droplets or a large
//! mesh can take minutes) nothing has been rendered, so brume exits at once with 130. While
//! rendering, the first stops the pass in flight (the engine never adds a partial pass to the
//! film), then brume saves the completed passes and exits 130; a second aborts at once.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// Exit status of an interrupted render (the shell convention for SIGINT).
pub const INTERRUPTED: u8 = 130;

/// The flags the handler shares with the render.
pub struct Interrupt {
    /// Set by the first interrupt while rendering: the engine stops the pass in flight.
    pub stop: Arc<AtomicBool>,
    /// False during setup, when an interrupt exits at once.
    rendering: Arc<AtomicBool>,
}

impl Interrupt {
    /// From now on an interrupt stops the render and saves its passes instead of exiting.
    pub fn rendering_starts(&self) {
        self.rendering.store(true, Ordering::SeqCst);
    }
}

/// Installs the handler. Called first thing, so that a signal during scene loading and building
/// is caught as well.
pub fn install(quiet: bool) -> Interrupt {
    let stop = Arc::new(AtomicBool::new(false));
    let rendering = Arc::new(AtomicBool::new(false));
    let count = AtomicUsize::new(0);
    let (flag, phase) = (stop.clone(), rendering.clone());
    let result = ctrlc::set_handler(move || {
        if !phase.load(Ordering::SeqCst) {
            // Outputs are written only after rendering (at most the empty file that checked a
            // folder is writable can be left, and the next run on that output removes it).
            eprintln!("\nbrume: interrupted during setup, before any pass: nothing written");
            std::process::exit(INTERRUPTED as i32);
        }
        if count.fetch_add(1, Ordering::SeqCst) == 0 {
            flag.store(true, Ordering::SeqCst);
            if !quiet {
                eprintln!(
                    "\nbrume: interrupt: stopping the pass in flight, then saving the completed \
                     passes (interrupt again to abort without saving)"
                );
            }
        } else {
            eprintln!("\nbrume: aborted");
            std::process::exit(INTERRUPTED as i32);
        }
    });
    if let Err(e) = result {
        eprintln!("brume: warning: cannot catch interrupts ({e}); Ctrl-C will lose the render");
    }
    Interrupt { stop, rendering }
}
