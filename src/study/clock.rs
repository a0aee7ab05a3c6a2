//! The study's time budgets: wall-clock seconds (`--time`) and process CPU seconds
//! (`--cpu-time`), and the clock efficiencies are measured on.
//!
//! CPU time is the user plus system time of the whole process (every thread: the rayon workers
//! that render, and their brief spinning between jobs) as `getrusage(RUSAGE_SELF)` reports it,
//! counted only while passes render. On a loaded machine it is steadier than wall time: waiting
//! for a core is not counted, though cache and memory contention still are.

use std::sync::atomic::{AtomicBool, Ordering};

use serde::Serialize;

use super::StudyError;

/// Which clock a study's efficiencies (1 / (MSE x t)) use.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Clock {
    /// Wall-clock seconds of pass rendering.
    Wall,
    /// Process CPU seconds (user + system, all threads) of pass rendering.
    Cpu,
}

impl Clock {
    pub fn name(self) -> &'static str {
        match self {
            Clock::Wall => "wall-clock seconds",
            Clock::Cpu => "CPU seconds",
        }
    }
}

/// Time spent rendering passes so far, on both clocks (`cpu` is NaN where the platform has no
/// process CPU clock).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Elapsed {
    pub wall: f64,
    pub cpu: f64,
}

impl Elapsed {
    pub fn on(&self, clock: Clock) -> f64 {
        match clock {
            Clock::Wall => self.wall,
            Clock::Cpu => self.cpu,
        }
    }
}

/// How long each run renders: until any of the given budgets is spent (at least one pass).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Budget {
    /// Wall-clock seconds per run.
    pub wall: Option<f64>,
    /// Process CPU seconds per run.
    pub cpu: Option<f64>,
}

impl Budget {
    pub fn wall(seconds: f64) -> Self {
        Self {
            wall: Some(seconds),
            cpu: None,
        }
    }

    pub fn cpu(seconds: f64) -> Self {
        Self {
            wall: None,
            cpu: Some(seconds),
        }
    }

    /// The clock efficiencies are measured on: CPU time when a CPU budget is set.
    pub fn clock(&self) -> Clock {
        match self.cpu {
            Some(_) => Clock::Cpu,
            None => Clock::Wall,
        }
    }

    /// Refuses budgets that are not positive numbers, and a CPU budget where the process CPU
    /// clock cannot be read.
    pub fn check(&self) -> Result<(), StudyError> {
        let bad = |flag: &str, v: f64| {
            (!(v.is_finite() && v > 0.0))
                .then(|| StudyError::Budget(format!("{flag} {v}: expected a positive number")))
        };
        if let Some(e) = self.wall.and_then(|v| bad("--time", v)) {
            return Err(e);
        }
        if let Some(e) = self.cpu.and_then(|v| bad("--cpu-time", v)) {
            return Err(e);
        }
        if self.cpu.is_some() && process_cpu_seconds().is_none() {
            return Err(StudyError::Budget(
                "--cpu-time: this platform has no process CPU clock (getrusage)".into(),
            ));
        }
        Ok(())
    }

    /// Whether a run that has rendered for `e` is done.
    pub fn spent(&self, e: Elapsed) -> bool {
        let wall = self.wall.is_some_and(|w| e.wall >= w);
        let cpu = self.cpu.is_some_and(|c| e.cpu >= c);
        wall || cpu || (self.wall.is_none() && self.cpu.is_none())
    }

    /// What is left of the budget after `e` (a budget that is already spent stops at once).
    pub fn left(&self, e: Elapsed) -> Budget {
        Budget {
            wall: self.wall.map(|w| w - e.wall),
            cpu: self.cpu.map(|c| c - e.cpu),
        }
    }

    /// Whether a run that took `e` went over the budget by more than the time it takes to
    /// abandon a pass in flight (a few per cent, or 0.1 s): only a first pass longer than the
    /// budget does that, as a run needs one whole pass for an image.
    pub fn overrun(&self, e: Elapsed) -> bool {
        let over = |b: Option<f64>, t: f64| b.is_some_and(|b| t > b * 1.05 + 0.1);
        over(self.wall, e.wall) || over(self.cpu, e.cpu)
    }

    /// Fraction of the budget spent (the larger of the two), in [0, 1].
    pub fn fraction(&self, e: Elapsed) -> f64 {
        let f = |b: Option<f64>, t: f64| b.map_or(0.0, |b| if t.is_finite() { t / b } else { 0.0 });
        f(self.wall, e.wall).max(f(self.cpu, e.cpu)).clamp(0.0, 1.0)
    }
}

/// How a pass of [`run_budgeted`] ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PassEnd {
    /// The pass is whole and in the film.
    Done,
    /// The budget ran out inside the pass: it was abandoned (the film is as before it).
    Stopped,
    /// The pass could not be rendered (not for lack of time).
    Failed,
}

/// Renders passes (`pass(stop)` returns whether the pass completed) until `budget` is spent,
/// calling `each(elapsed, last)` after every pass. Equal time means equal time: from the second
/// pass on, a watchdog sets `stop` as soon as the budget runs out, so the pass in flight is
/// abandoned and the run ends at its budget (its last call then sees the film of the passes
/// completed, with the whole time spent). The first pass always completes, as a run needs an
/// image: a first pass longer than the budget is the only way over it ([`Budget::overrun`]).
/// Returns the time spent and how the last pass ended.
pub(crate) fn run_budgeted(
    budget: Budget,
    mut pass: impl FnMut(&AtomicBool) -> bool,
    mut each: impl FnMut(Elapsed, bool),
) -> (Elapsed, PassEnd) {
    let mut spent = Elapsed::default();
    let mut first = true;
    loop {
        let stop = AtomicBool::new(false);
        let done = AtomicBool::new(false);
        let left = budget.left(spent);
        let (completed, t) = std::thread::scope(|s| {
            if !first {
                s.spawn(|| watch(left, &stop, &done));
            }
            let mut completed = false;
            let t = timed(|| completed = pass(&stop));
            done.store(true, Ordering::SeqCst);
            (completed, t)
        });
        first = false;
        spent.wall += t.wall;
        spent.cpu += t.cpu;
        let end = match (completed, stop.load(Ordering::SeqCst)) {
            (true, _) => PassEnd::Done,
            (false, true) => PassEnd::Stopped,
            (false, false) => PassEnd::Failed,
        };
        let last = end != PassEnd::Done || budget.spent(spent);
        if end != PassEnd::Failed {
            each(spent, last);
        }
        if last {
            return (spent, end);
        }
    }
}

/// Sets `stop` once `left` is spent, measured from now, unless `done` is set first.
fn watch(left: Budget, stop: &AtomicBool, done: &AtomicBool) {
    let t0 = std::time::Instant::now();
    let c0 = process_cpu_seconds();
    while !done.load(Ordering::SeqCst) {
        let cpu = match (c0, process_cpu_seconds()) {
            (Some(a), Some(b)) => b - a,
            _ => f64::NAN,
        };
        let e = Elapsed {
            wall: t0.elapsed().as_secs_f64(),
            cpu,
        };
        if left.spent(e) {
            stop.store(true, Ordering::SeqCst);
            return;
        }
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
}

/// User plus system CPU seconds of this process so far (all threads); None where unavailable.
#[cfg(unix)]
pub fn process_cpu_seconds() -> Option<f64> {
    use nix::sys::resource::{UsageWho, getrusage};
    use nix::sys::time::TimeValLike;
    let u = getrusage(UsageWho::RUSAGE_SELF).ok()?;
    let micros = u.user_time().num_microseconds() + u.system_time().num_microseconds();
    Some(micros as f64 * 1e-6)
}

/// User plus system CPU seconds of this process so far (all threads); None where unavailable.
#[cfg(not(unix))]
pub fn process_cpu_seconds() -> Option<f64> {
    None
}

/// Measures the time of one piece of work on both clocks.
pub(crate) fn timed(work: impl FnOnce()) -> Elapsed {
    let cpu0 = process_cpu_seconds();
    let t0 = std::time::Instant::now();
    work();
    let wall = t0.elapsed().as_secs_f64();
    let cpu = match (cpu0, process_cpu_seconds()) {
        (Some(a), Some(b)) => (b - a).max(0.0),
        _ => f64::NAN,
    };
    Elapsed { wall, cpu }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn timed_counts_cpu_seconds_of_busy_work() {
        if process_cpu_seconds().is_none() {
            return; // no CPU clock on this platform: nothing to measure
        }
        // Other tests of this binary run in parallel threads and add to the process's CPU
        // time, so only the lower bound is checked here (the CLI test checks the upper one in
        // a process of its own).
        let mut x = 0u64;
        // The loop starts its own count inside `timed`, whose clock starts first, so the time
        // measured cannot fall short of the 0.05 s spent.
        let busy = timed(|| {
            let start = process_cpu_seconds().unwrap_or(0.0);
            while process_cpu_seconds().is_some_and(|t| t < start + 0.05) {
                x = std::hint::black_box(x.wrapping_mul(6364136223846793005).wrapping_add(1));
            }
        });
        // 1e-9 s: the two clock readings are subtracted in f64, which can round 0.05 s of
        // work to 0.04999999999999982 (seen on CI).
        assert!(busy.cpu >= 0.05 - 1e-9 && busy.cpu < 60.0, "{busy:?}");
        assert!(busy.wall > 0.0);
    }

    #[test]
    fn budgets_stop_at_the_first_spent_and_report_fractions() {
        let both = Budget {
            wall: Some(10.0),
            cpu: Some(2.0),
        };
        assert_eq!(both.clock(), Clock::Cpu);
        assert_eq!(Budget::wall(1.0).clock(), Clock::Wall);
        let e = |wall, cpu| Elapsed { wall, cpu };
        assert!(!both.spent(e(1.0, 1.0)));
        assert!(both.spent(e(1.0, 2.0)));
        assert!(both.spent(e(10.0, 0.5)));
        assert!(!Budget::wall(1.0).spent(e(0.5, 100.0)));
        assert!(Budget::cpu(1.0).spent(e(0.1, 1.0)));
        assert_eq!(both.fraction(e(5.0, 0.5)), 0.5);
        assert_eq!(both.fraction(e(50.0, 0.5)), 1.0);
        assert_eq!(Budget::wall(2.0).fraction(e(1.0, f64::NAN)), 0.5);
        assert!(Budget::wall(-1.0).check().is_err());
        assert!(Budget::cpu(f64::NAN).check().is_err());
        assert!(Budget::wall(0.5).check().is_ok());
        assert!(!Budget::wall(4.0).overrun(e(4.15, 9.0)));
        assert!(Budget::wall(4.0).overrun(e(15.8, 9.0)));
        assert!(Budget::cpu(4.0).overrun(e(1.0, 15.8)));
    }

    /// A pass of `seconds` that gives up when `stop` is set (as `render_pass_until` does).
    fn sleepy_pass(seconds: f64) -> impl FnMut(&AtomicBool) -> bool {
        move |stop| {
            let t0 = std::time::Instant::now();
            while t0.elapsed().as_secs_f64() < seconds {
                if stop.load(Ordering::SeqCst) {
                    return false;
                }
                std::thread::sleep(std::time::Duration::from_millis(1));
            }
            true
        }
    }

    #[test]
    fn a_run_stops_inside_a_pass_at_its_budget() {
        // Passes of 0.4 s against a 0.5 s budget: whole passes ran to 0.8 s (issue 31: 4 s
        // budgets ran to 15.8 s). Now the second pass is abandoned at 0.5 s; the last call
        // sees the one whole pass with the whole time spent.
        let mut calls = Vec::new();
        let (spent, end) = run_budgeted(Budget::wall(0.5), sleepy_pass(0.4), |e, last| {
            calls.push((e.wall, last))
        });
        assert_eq!(end, PassEnd::Stopped);
        assert!(spent.wall >= 0.5 && spent.wall < 0.7, "{spent:?}");
        assert_eq!(calls.len(), 2, "{calls:?}");
        assert!(!calls[0].1 && calls[1].1, "{calls:?}");
        assert!(!Budget::wall(0.5).overrun(spent));
    }

    #[test]
    fn a_first_pass_longer_than_the_budget_completes_and_is_an_overrun() {
        let mut calls = 0;
        let (spent, end) = run_budgeted(Budget::wall(0.1), sleepy_pass(0.4), |_, last| {
            calls += 1;
            assert!(last);
        });
        assert_eq!((end, calls), (PassEnd::Done, 1));
        assert!(Budget::wall(0.1).overrun(spent), "{spent:?}");
        // A pass that fails for another reason than the budget ends the run without a call.
        let (_, end) = run_budgeted(Budget::wall(1.0), |_| false, |_, _| panic!("no pass"));
        assert_eq!(end, PassEnd::Failed);
    }
}
