//! Running a render for Python: the library's `Renderer` on a thread of its own while the
//! calling thread, which holds the interpreter between waits, reports progress and watches for
//! Ctrl-C (Python's signal handlers run only there). The interpreter is free while waiting, so
//! other Python threads (a Dask worker's heartbeat) go on.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::Duration;

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use brume::film::{Film, FilmId};
use brume::integrator::{Budget, MAX_PASS_END, Renderer};
use brume::scene::LoadedScene;

use crate::RenderError;
use crate::result::RenderResult;

/// More worker threads than this is a typo, as on the command line (`--threads`).
const MAX_THREADS: i64 = 1024;

/// One render in the process at a time: a render uses every core it is given, and two would
/// share the signal handling and the progress of one interpreter.
static RENDERING: AtomicBool = AtomicBool::new(false);

/// What to render, checked before anything is built.
pub struct Request {
    budget: Budget,
    first: u64,
    seed: u64,
    threads: usize,
}

fn value_error(msg: String) -> PyErr {
    PyValueError::new_err(msg)
}

impl Request {
    pub fn new(
        loaded: &LoadedScene,
        passes: Option<i64>,
        time: Option<f64>,
        seed: Option<i64>,
        threads: Option<i64>,
        pass_range: Option<(i64, i64)>,
    ) -> PyResult<Self> {
        let budget = match (pass_range, passes, time) {
            (Some(_), Some(_), _) | (Some(_), _, Some(_)) | (None, Some(_), Some(_)) => {
                return Err(value_error(
                    "give one of passes, time and pass_range (pass_range fixes the passes)".into(),
                ));
            }
            (Some((a, b)), None, None) => {
                if a < 0 || a >= b || b as u64 > MAX_PASS_END {
                    return Err(value_error(format!(
                        "pass_range ({a}, {b}): expected (A, B) with 0 <= A < B <= {MAX_PASS_END}"
                    )));
                }
                Budget::Passes((b - a) as u32)
            }
            (None, Some(p), None) => {
                if p < 1 || p as u64 > MAX_PASS_END {
                    return Err(value_error(format!(
                        "passes={p}: expected a whole number from 1 to {MAX_PASS_END}"
                    )));
                }
                Budget::Passes(p as u32)
            }
            (None, None, Some(t)) => {
                if !(t.is_finite() && t > 0.0) {
                    return Err(value_error(format!(
                        "time={t}: expected a positive number of seconds"
                    )));
                }
                Budget::Time(t)
            }
            (None, None, None) => Budget::Passes(loaded.desc.integrator.passes),
        };
        let seed = match seed {
            None => loaded.desc.integrator.seed,
            Some(s) if s >= 0 => s as u64,
            Some(s) => return Err(value_error(format!("seed={s}: seeds are 0 or more"))),
        };
        let threads = match threads.unwrap_or(0) {
            n @ 0..=MAX_THREADS => n as usize,
            n => {
                return Err(value_error(format!(
                    "threads={n}: expected 0 (every core) to {MAX_THREADS}"
                )));
            }
        };
        let first = pass_range.map_or(0, |(a, _)| a as u64);
        Ok(Self {
            budget,
            first,
            seed,
            threads,
        })
    }
}

/// Frees the one-render slot when the render ends, however it ends.
struct Slot;

impl Slot {
    fn take() -> PyResult<Self> {
        RENDERING
            .compare_exchange(false, true, Ordering::SeqCst, Ordering::SeqCst)
            .map(|_| Slot)
            .map_err(|_| {
                RenderError::new_err(
                    "another render is running in this process: brume renders one scene at a \
                     time per process (each uses every core it is given); wait for it, or \
                     render in another process",
                )
            })
    }
}

impl Drop for Slot {
    fn drop(&mut self) {
        RENDERING.store(false, Ordering::SeqCst);
    }
}

/// What the render thread tells the calling thread.
enum Message {
    Warning(String),
    /// Passes in the film, seconds since the first pass started.
    Progress(u64, f64),
}

/// The render thread's result, or why the scene could not be built (a texture, mesh or
/// spectrum file).
type Outcome = Result<Rendered, brume::scene::SceneError>;

/// What a render that ran gives back (see [`Outcome`]).
struct Rendered {
    film: Film,
    /// The row over the gather budget that stopped the render, if one did.
    failure: Option<String>,
    /// How the passes sampled: the resolved q, forward rays, camera paths and radius.
    settings: serde_json::Value,
}

/// Builds and renders `loaded` on a thread of its own (see the module's comment).
pub fn render(
    py: Python<'_>,
    loaded: &LoadedScene,
    req: &Request,
    progress: Option<Bound<'_, PyAny>>,
) -> PyResult<RenderResult> {
    let _slot = Slot::take()?;
    let progress = reporter(py, progress, req)?;
    let id = brume::scene::identity::film_id(loaded, req.seed)
        .map_err(|e| RenderError::new_err(e.to_string()))?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(req.threads)
        .build()
        .map_err(|e| RenderError::new_err(format!("cannot start worker threads: {e}")))?;
    let stop = AtomicBool::new(false);
    let (tx, rx) = mpsc::channel();
    let total = match req.budget {
        Budget::Passes(p) => p as u64,
        Budget::Time(t) => t.ceil() as u64,
    };
    let outcome = std::thread::scope(|s| -> PyResult<Outcome> {
        let worker = s.spawn(|| pool.install(|| run(loaded, &id, req, &stop, tx)));
        let watched = watch(py, rx, &stop, req, total, progress.as_ref());
        if let Some(p) = &progress
            && p.bind(py).hasattr("close")?
        {
            p.call_method0(py, "close")?;
        }
        // The render stops within a pixel or 256 forward rays once `stop` is set.
        let outcome = py.detach(|| worker.join());
        watched?;
        outcome.map_err(|_| RenderError::new_err("the render thread panicked (a bug in brume)"))
    })?;
    let Rendered {
        film,
        failure,
        settings,
    } = outcome.map_err(crate::scene::scene_error)?;
    if let Some(e) = failure {
        return Err(RenderError::new_err(format!(
            "{e} (the {} completed passes are not returned)",
            film.passes
        )));
    }
    RenderResult::new(film, id, Some(settings))
}

/// The progress callable: True (or not given) gives brume._progress's bar, False none.
fn reporter(
    py: Python<'_>,
    progress: Option<Bound<'_, PyAny>>,
    req: &Request,
) -> PyResult<Option<Py<PyAny>>> {
    let progress =
        progress.unwrap_or_else(|| pyo3::types::PyBool::new(py, true).to_owned().into_any());
    if let Ok(on) = progress.cast::<pyo3::types::PyBool>() {
        if !on.is_true() {
            return Ok(None);
        }
        let (total, unit) = match req.budget {
            Budget::Passes(p) => (p as u64, "passes"),
            Budget::Time(t) => (t.ceil() as u64, "s"),
        };
        let bar = py
            .import("brume._progress")?
            .call_method1("bar", (total, unit))?;
        return Ok(Some(bar.unbind()));
    }
    if !progress.is_callable() {
        return Err(pyo3::exceptions::PyTypeError::new_err(
            "progress: expected True, False or a callable progress(done, total, passes)",
        ));
    }
    Ok(Some(progress.unbind()))
}

/// Waits for the render thread's messages with the interpreter free, reporting progress and
/// warnings, until the thread ends; Ctrl-C (or an exception from `progress`) sets `stop` and
/// is returned once the thread has ended.
fn watch(
    py: Python<'_>,
    mut rx: mpsc::Receiver<Message>,
    stop: &AtomicBool,
    req: &Request,
    total: u64,
    progress: Option<&Py<PyAny>>,
) -> PyResult<()> {
    let mut failed: Option<PyErr> = None;
    loop {
        // The receiver goes to the waiting side and back: it is not shared between threads.
        let (back, msg) = py.detach(move || {
            let msg = rx.recv_timeout(Duration::from_millis(100));
            (rx, msg)
        });
        rx = back;
        let result = match msg {
            Ok(Message::Warning(w)) => warn(py, &w),
            Ok(Message::Progress(passes, elapsed)) => match progress {
                Some(cb) => {
                    let done = match req.budget {
                        Budget::Passes(_) => passes,
                        Budget::Time(_) => (elapsed as u64).min(total),
                    };
                    cb.call1(py, (done, total, passes)).map(|_| ())
                }
                None => Ok(()),
            },
            Err(mpsc::RecvTimeoutError::Timeout) => Ok(()),
            Err(mpsc::RecvTimeoutError::Disconnected) => break,
        };
        let result = result.and_then(|_| py.check_signals());
        if let (Err(e), None) = (result, &failed) {
            stop.store(true, Ordering::SeqCst);
            failed = Some(e);
        }
    }
    failed.map_or(Ok(()), Err)
}

fn warn(py: Python<'_>, message: &str) -> PyResult<()> {
    let category = py.get_type::<pyo3::exceptions::PyUserWarning>();
    let text = std::ffi::CString::new(message.replace('\0', " ")).unwrap_or_default();
    PyErr::warn(py, &category, &text, 1)
}

/// The render thread: builds the scene and renders the request's passes.
fn run(
    loaded: &LoadedScene,
    id: &FilmId,
    req: &Request,
    stop: &AtomicBool,
    tx: mpsc::Sender<Message>,
) -> Outcome {
    let (scene, warnings) = brume::scene::build_with_warnings(loaded)?;
    for w in &warnings {
        let _ = tx.send(Message::Warning(format!("brume: warning: {w}")));
    }
    let integrator = brume::scene::build_integrator(loaded, &scene)?;
    let mut renderer = Renderer::starting_at(&scene, integrator, id.seed, req.first);
    // Whether it stopped early matters only for an interrupt, which `watch` reports.
    let _stopped = renderer.run_until(req.budget, stop, |film, elapsed| {
        let _ = tx.send(Message::Progress(film.passes, elapsed));
    });
    let i = renderer.integrator();
    let settings = serde_json::json!({
        "q": i.q,
        "forward_rays": i.forward_rays,
        "camera_samples": i.camera_samples,
        "radius": i.radius.r0,
        // The radius for scattered light (the pilots may choose 2x): pinning q and the
        // budgets without it would render at the single radius.
        "radius_indirect": i.radius.r0 * i.indirect_scale,
    });
    Ok(Rendered {
        failure: renderer.over_budget().map(|e| e.to_string()),
        settings,
        film: renderer.into_film(),
    })
}
