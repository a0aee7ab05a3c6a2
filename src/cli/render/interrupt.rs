//! Ctrl-C and SIGTERM: the first abandons the pass in flight (the engine never adds a partial
//! pass to the film; it stops between rows and chunks of rays, so it never waits for a long
//! pass), then brume saves the passes it has and exits 130; a second aborts at once.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// Exit status of an interrupted render (the shell convention for SIGINT).
pub const INTERRUPTED: u8 = 130;

/// Installs the handler and returns the flag it sets. Called first thing, so that a signal
/// during scene loading and building is caught as well (the render then stops before its
/// first pass).
pub fn install(quiet: bool) -> Arc<AtomicBool> {
    let stop = Arc::new(AtomicBool::new(false));
    let count = AtomicUsize::new(0);
    let flag = stop.clone();
    let result = ctrlc::set_handler(move || {
        if count.fetch_add(1, Ordering::SeqCst) == 0 {
            flag.store(true, Ordering::SeqCst);
            if !quiet {
                eprintln!(
                    "\nbrume: interrupt: abandoning the pass in flight, then saving the \
                     passes done (interrupt again to abort without saving)"
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
    stop
}
