//! The pass loop: camera pass -> gather structure -> light pass -> film, until a budget of
//! passes or wall-clock time is spent. Each pass's radii follow the schedule of `radius`.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use super::auto::{Choice, ChoiceChanged, PilotResult, Tuner, Work, settings_of};
use super::camera_pass::OverBudget;
use super::light_pass::LightJob;
use super::nest::NestCounts;
use super::sensors::{SensorJob, SensorPass, SensorPoint, sensor_points};
use super::{Integrator, Radii};
use crate::film::{Film, PassBuffer, SpectralImage};
use crate::world::Scene;

/// Pass indices stay below this: the pass budget counts in u32, and a range starting near
/// 2^53 would not even be exact in the f64 statistics of the film. Every front end (the CLI's
/// `--pass-range`, the Python package's `pass_range`) checks against this one bound.
pub const MAX_PASS_END: u64 = u32::MAX as u64;

/// How much to render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Budget {
    Passes(u32),
    /// Seconds of wall-clock time; whole passes, at least one.
    Time(f64),
}

/// Counters of a render, for reports and benchmarks.
#[derive(Clone, Copy, Debug, Default)]
pub struct Stats {
    pub camera_paths: u64,
    pub surface_records: u64,
    pub volume_records: u64,
    pub forward_rays: u64,
    /// Gather candidates the forward rays met (surface spheres and volumes tested).
    pub gather_hits: u64,
    /// Segments the forward rays traced.
    pub forward_segments: u64,
    /// Paths traced from illuminance sensors.
    pub sensor_paths: u64,
    pub peak_gather_bytes: usize,
    /// Peak bytes of building a tile's gather as the budget counts them
    /// (`gather::peak_bytes_for`): at most `integrator.max_gather_bytes`.
    pub peak_build_bytes: usize,
    pub camera_seconds: f64,
    pub build_seconds: f64,
    pub light_seconds: f64,
    /// Gather tiles traced (more than one per pass when the memory budget splits passes).
    pub tiles: u64,
    /// Pilot passes of automatic settings rendered again, not added (a resumed render or a
    /// part that starts after them).
    pub pilot_passes: u64,
}

impl Stats {
    /// Adds a gather tile's camera paths, forward rays and the light pass's counts, and the
    /// times of its phases (camera pass, gather build, light pass).
    fn add_tile(&mut self, paths: u64, rays: u64, light: &LightJob, t: [Instant; 4]) {
        self.gather_hits += light.hits.load(Ordering::Relaxed);
        self.forward_segments += light.segments.load(Ordering::Relaxed);
        self.camera_paths += paths;
        self.forward_rays += rays;
        self.camera_seconds += (t[1] - t[0]).as_secs_f64();
        self.build_seconds += (t[2] - t[1]).as_secs_f64();
        self.light_seconds += (t[3] - t[2]).as_secs_f64();
        self.tiles += 1;
    }
}

/// Renders passes of a scene with an integrator into a film.
pub struct Renderer<'a> {
    scene: &'a Scene,
    integrator: Integrator,
    seed: u64,
    film: Film,
    radii: Radii,
    /// Chooses the `"auto"` settings from pilot passes (None when there are none).
    tuner: Option<Tuner>,
    /// The scene's illuminance sensors.
    sensors: Vec<SensorPoint>,
    /// Set when a pass was abandoned because one row of camera paths exceeded the gather
    /// budget: every later pass would be too (see `over_budget`).
    over_budget: Option<OverBudget>,
    /// Set when the film's passes were rendered with another automatic choice than the
    /// pilots make now (see `choice_changed`).
    choice_changed: Option<ChoiceChanged>,
    /// Told the number of records before a gather too large to build at once is built (the
    /// CLI's `--verbose` prints it: the build is the one silent phase of a pass).
    on_large_build: Option<Box<dyn FnMut(usize) + 'a>>,
    pub stats: Stats,
}

impl<'a> Renderer<'a> {
    pub fn new(scene: &'a Scene, integrator: Integrator, seed: u64) -> Self {
        let (w, h) = scene.camera.resolution();
        Self {
            scene,
            seed,
            film: Film::with_extras(
                w as usize,
                h as usize,
                scene.grid.clone(),
                0,
                scene.film_extras.clone(),
            ),
            radii: integrator.radii(0),
            tuner: Tuner::new(
                &integrator.settings,
                scene.media.len(),
                integrator.pass_config(),
                (w, h),
            ),
            sensors: sensor_points(scene),
            integrator,
            over_budget: None,
            choice_changed: None,
            on_large_build: None,
            stats: Stats::default(),
        }
    }

    /// A renderer whose first pass is pass `first` of the seed's sequence (a slice of a
    /// distributed render, see `Film::merge`).
    pub fn starting_at(scene: &'a Scene, integrator: Integrator, seed: u64, first: u64) -> Self {
        let mut r = Self::new(scene, integrator, seed);
        r.film.first = first;
        r.radii = r.integrator.radii(first);
        r
    }

    /// A renderer that continues `film` (restored from a checkpoint): the next pass is
    /// `film.end()`, rendered exactly as an uninterrupted run would render it. Fails when the
    /// film's size, spectral grid, sensors or light layers are not the scene's.
    pub fn resume(
        scene: &'a Scene,
        integrator: Integrator,
        seed: u64,
        film: Film,
    ) -> Result<Self, String> {
        let mut r = Self::new(scene, integrator, seed);
        if (film.width, film.height, &film.grid) != (r.film.width, r.film.height, &r.film.grid) {
            return Err(format!(
                "the film is {}x{} pixels with {} bins, the scene renders {}x{} with {}",
                film.width, film.height, film.grid.n, r.film.width, r.film.height, r.film.grid.n
            ));
        }
        if film.extras != r.film.extras {
            return Err("the film keeps other sensors or light layers than the scene".into());
        }
        r.radii = r.integrator.radii(film.end());
        r.film = film;
        Ok(r)
    }

    /// Calls `f` with the number of records before each gather large enough to be built on a
    /// thread of its own (`Gather::builds_apart`), the part of a pass that reports no progress.
    pub fn on_large_build(&mut self, f: impl FnMut(usize) + 'a) {
        self.on_large_build = Some(Box::new(f));
    }

    /// Why passes stopped being added, other than `stop`: a row of camera paths that alone
    /// needs more gather memory than `integrator.max_gather_bytes` (the render cannot go on
    /// within the budget; `run_until` stops, `render_pass` adds nothing).
    pub fn over_budget(&self) -> Option<&OverBudget> {
        self.over_budget.as_ref()
    }

    /// Why no pass was added to a resumed film: its passes were rendered with another
    /// automatic choice than this brume's pilot passes make (`run_until` stops before the
    /// first pass).
    pub fn choice_changed(&self) -> Option<&ChoiceChanged> {
        self.choice_changed.as_ref()
    }

    /// The counters of the passes rendered so far.
    pub fn stats(&self) -> &Stats {
        &self.stats
    }

    pub fn film(&self) -> &Film {
        &self.film
    }

    /// Gives the film away (for saving) without copying it.
    pub fn into_film(self) -> Film {
        self.film
    }

    pub fn image(&self) -> SpectralImage {
        self.film.image()
    }

    /// The integrator rendering the passes.
    pub fn integrator(&self) -> &Integrator {
        &self.integrator
    }

    /// The radius the next pass will use (its direct light's, see [`Radii`]).
    pub fn radius(&self) -> f32 {
        self.radii.direct
    }

    /// The radii the next pass will use.
    pub fn radii(&self) -> Radii {
        self.radii
    }

    /// Renders pass number `self.film.end()` and adds it to the film. When the gather records
    /// of the whole image would exceed `integrator.max_gather_bytes`, the pass is split into
    /// tiles of rows, each with its own gather structure and light pass.
    pub fn render_pass(&mut self) {
        self.render_pass_until(&AtomicBool::new(false));
    }

    /// `render_pass`, abandoned (nothing added to the film, false returned) as soon as `stop`
    /// is set: checked before every pixel of the camera pass, before the gather structure is
    /// built and every 256 forward rays, so that an interrupt never waits for a long pass.
    ///
    /// With automatic budgets, film pass `p` is pass `p + P` of the seed's sequence, where the
    /// first P are the tuner's pilot passes, rendered before the first film pass of every
    /// process (fresh, resumed or a part) and left out of the film: a pilot at the base budgets
    /// can carry many times a chosen pass's variance (fog-cube: 1 camera path per pixel, 14x),
    /// and the film weighs its passes equally. With q alone automatic, the pilots sample at the
    /// scene's budgets and are film passes like any other (`Tuner::pilots_join_film`).
    pub fn render_pass_until(&mut self, stop: &AtomicBool) -> bool {
        let pass = self.film.end();
        let seq = pass + self.tuner.as_ref().map_or(0, Tuner::film_offset);
        if !self.prepare(seq, stop) || !self.configure(seq) {
            return false;
        }
        let Some((buf, work, counts)) = self.render_into(seq, pass, stop) else {
            return false;
        };
        if let Some(t) = &mut self.tuner {
            let result = PilotResult::from_pass(&buf, work, t.nest(seq), &counts);
            t.record(seq, result);
        }
        self.film.add_pass(&buf);
        self.keep_choice()
    }

    /// Puts the automatic settings' choice on the film once it is made, so that the film's
    /// checkpoints and parts carry it to their images (`Film::auto_settings`). False when the
    /// film records another choice (a film another brume began, whose pilots chose
    /// differently): its passes and this brume's would mix two configurations while its
    /// images name one (`choice_changed`).
    fn keep_choice(&mut self) -> bool {
        let Some(c) = self.tuner.as_ref().and_then(Tuner::choice) else {
            return true;
        };
        let now = settings_of(&c.config);
        match self.film.auto_choice() {
            None if self.film.auto_settings.is_empty() => {
                self.film.auto_settings = c.report.clone();
                true
            }
            Some(film) if film != now => {
                let film = film.to_string();
                self.choice_changed = Some(ChoiceChanged { film, now });
                false
            }
            None | Some(_) => true,
        }
    }

    /// Renders, without adding them to the film, the pilot passes before pass `seq` of the
    /// sequence that this process has not recorded (a resumed render, a part, or every pilot
    /// when they are not film passes), so that it chooses exactly as any other process does.
    fn prepare(&mut self, seq: u64, stop: &AtomicBool) -> bool {
        let Some((mut next, pilots)) = self
            .tuner
            .as_ref()
            .map(|t| (t.recorded(), t.pilot_passes()))
        else {
            return true;
        };
        while next < seq.min(pilots) {
            if !self.configure(next) {
                return false;
            }
            let Some((buf, work, counts)) = self.render_into(next, next, stop) else {
                return false;
            };
            self.stats.pilot_passes += 1;
            if let Some(t) = &mut self.tuner {
                let result = PilotResult::from_pass(&buf, work, t.nest(next), &counts);
                t.record(next, result);
            }
            if !self.keep_choice() {
                return false;
            }
            next += 1;
        }
        true
    }

    /// Applies the tuner's configuration of `pass` (false if it cannot be built).
    fn configure(&mut self, pass: u64) -> bool {
        let Some(c) = self.tuner.as_ref().and_then(|t| t.config(pass)).cloned() else {
            return true;
        };
        self.integrator.apply(&c, &self.scene.media).is_ok()
    }

    /// The automatic settings' choice and the estimates behind it, once the pilot passes are
    /// done (None without automatic settings).
    pub fn auto_choice(&self) -> Option<&Choice> {
        self.tuner.as_ref().and_then(Tuner::choice)
    }

    /// Renders pass `pass` of the seed's sequence with the integrator as configured, at the
    /// radius of film pass `film_pass`, or None when `stop` was set. A pilot outside the film
    /// draws the random numbers of another pass (`Tuner::random_pass`); a pilot with nested
    /// estimates (`Tuner::nest`) also forms theirs, and counts their work.
    fn render_into(
        &mut self,
        pass: u64,
        film_pass: u64,
        stop: &AtomicBool,
    ) -> Option<(PassBuffer, Work, NestCounts)> {
        let nest = self.tuner.as_ref().and_then(|t| t.nest(pass)).cloned();
        let sampling = self.sampling(pass);
        self.render_sampled(sampling, film_pass, nest.as_ref(), stop)
    }

    /// How pass `pass` of the sequence samples: the stride of its pixel lattice, and the pass
    /// whose random numbers it draws (its own, or a pilot's shared ones: `Tuner::random_pass`).
    fn sampling(&self, pass: u64) -> (u32, u64) {
        self.tuner
            .as_ref()
            .map_or((1, pass), |t| (t.pixel_stride(pass), t.random_pass(pass)))
    }

    /// The sensor paths of pass `pass` (Some(None) without illuminance sensors); None when
    /// `stop` was set.
    fn sensor_pass(&mut self, pass: u64, stop: &AtomicBool) -> Option<Option<SensorPass>> {
        if self.sensors.is_empty() {
            return Some(None);
        }
        let job = SensorJob {
            seed: self.seed,
            pass,
            radii: self.radii,
            points: &self.sensors,
        };
        let s = SensorPass::new(self.scene, &self.integrator, &job, stop)?;
        self.stats.sensor_paths += s.out.paths;
        Some(Some(s))
    }

    /// Renders until the budget is spent, calling `progress(passes_done, seconds)` after each pass.
    /// `Budget::Passes(p)` counts the passes in the film, including restored ones.
    pub fn run(&mut self, budget: Budget, mut progress: impl FnMut(u64, f64)) {
        self.run_until(budget, &AtomicBool::new(false), |film, t| {
            progress(film.passes, t)
        });
    }

    /// Like `run`, but stops once `stop` is set (an interrupt): the pass in flight is abandoned,
    /// so every pass in the film is whole. Returns true when stopped early. `after_pass(film, seconds)` sees the film after each pass (to report progress or
    /// save a checkpoint).
    pub fn run_until(
        &mut self,
        budget: Budget,
        stop: &AtomicBool,
        mut after_pass: impl FnMut(&Film, f64),
    ) -> bool {
        let start = Instant::now();
        loop {
            let done = match budget {
                Budget::Passes(p) => self.film.passes >= p as u64,
                // At least one pass even with a zero time budget.
                Budget::Time(t) => self.film.passes > 0 && start.elapsed().as_secs_f64() >= t,
            };
            if done {
                return false;
            }
            if stop.load(Ordering::SeqCst) || !self.render_pass_until(stop) {
                return true;
            }
            after_pass(&self.film, start.elapsed().as_secs_f64());
        }
    }
}

mod render;
#[cfg(test)]
mod tests;
