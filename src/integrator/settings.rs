//! The integrator's settings: the `[integrator]` table of a scene file, with every default, and
//! their checks. The scene file format embeds this type; the runtime reads it through
//! [`Integrator`](super::Integrator).

use serde::{Deserialize, Serialize};

use super::radius::Shrink;
use super::setting::Setting;
use crate::medium::{ChannelPick, Medium, Mixture};
use crate::spectrum::Spectrum;

/// The integration volume camera paths leave in media (`integrator.volume`); each is an
/// [`Estimator`](super::Estimator) variant.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum VolumeKind {
    /// Stochastic spheres along the camera segment; q = 1 is the single sphere at the extinction.
    #[default]
    Spheres,
    /// Deterministic transmittance over the whole first medium segment (paper eq. 2).
    Cylinder,
    /// Cylinder ending at the sampled extinction (method note 5b).
    CylinderTruncated,
    /// Paper eq. 3: deterministic attenuation along forward segments too.
    CylinderLong,
}

/// How the radius changes over the passes when `alpha` is 1 (`integrator.radius_schedule`;
/// `radius::Shrink`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum RadiusScheduleKind {
    /// Every pass at the starting radius: the paper's setting, whose images converge to the
    /// scene blurred over the radius.
    Fixed,
    /// Fixed for `shrink_after` passes, then falling as n^(-1/6): a consistent estimator.
    Consistent,
}

/// Passes at the starting radius before the consistent schedule shrinks it. The speed
/// protocol's 60 s renders at default settings run about 75 passes on fog-cube, 81 on
/// chromatic-cube, 406 on fog-room-laser and 740 on chromatic-fog (docs/performance.md): the
/// slow passes of large budgets, whose error is mostly noise, keep the radius the automatic
/// choice found efficient; many fast passes, where a fixed radius's blur becomes the error
/// left, shrink it.
pub const SHRINK_AFTER: u64 = 256;

/// Which light the medium's integration volumes collect (`integrator.mode`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum GatherMode {
    /// The camera path ends at its first medium extinction or diffuse surface.
    #[default]
    FirstExtinction,
    /// Volumes on the first medium segment gather direct/caustic light only; the path goes on
    /// through the medium to the diffuse surface behind, which gathers everything.
    SeeThrough,
}

/// Where the first numbers of each forward ray and camera path come from
/// (`integrator.sampler`; `rng` module comment).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Sampler {
    /// An Owen-scrambled Sobol point per forward ray and per camera path, scrambled anew in
    /// every pass: a pass's forward rays are stratified, and so are a pixel's camera paths of a
    /// pass. Pays with `direct = "photons"` (forward rays carry the direct light) and with
    /// several camera paths per pixel (chromatic-fog at 8: 3.6x lower per-pixel variance); at
    /// the scenes' own settings it measured no gain (docs/performance.md).
    Sobol,
    /// Independent pseudo-random numbers.
    #[default]
    Independent,
}

impl Sampler {
    /// Whether samples read Sobol points (`rng::Rng::begin_sample`).
    pub fn stratifies(self) -> bool {
        match self {
            Sampler::Sobol => true,
            Sampler::Independent => false,
        }
    }
}

/// Where a camera segment's integration spheres go (`integrator.placement`): both leave
/// `(1 - Tmix(T)) / q` spheres per segment on average and are unbiased per bin.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Placement {
    /// The paper's multiple-sphere walk (method note 2): exponential sub-steps, each ending in
    /// a real extinction with probability q.
    Walk,
    /// Stratified spheres (`medium::walk::stratified`): a fixed count per segment at
    /// stratified quantiles of the transmittance, the path's outcome sampled apart. Falls back
    /// to the walk in tracked media and in bins without extinction.
    Stratified,
}

/// How next-event estimation picks a light for each sample (`integrator.light_pick`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LightPick {
    /// In proportion to each light's estimated contribution at the receiver (`direct::pick`'s module comment).
    #[default]
    Local,
    /// In proportion to each light's total power, the same everywhere.
    Power,
}

/// How direct light (emitted, arriving through index-matched boundaries only) reaches the
/// image (`integrator.direct`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum DirectMode {
    /// Next-event estimation from camera paths for the lights that allow it (each light's
    /// `direct`, `auto` by default); forward rays of those lights gather only after their first
    /// scattering or surface event (method note 9).
    #[default]
    Nee,
    /// The paper's pure method: every light's forward rays gather from their emission on.
    Photons,
}

/// Gather memory per pass when `max_gather_bytes = 0`: a fixed figure, not a share of the
/// machine's memory, so that the same scene tiles its passes the same way (and so renders the
/// same bits) on every machine. 4 GiB holds about 15 million integration volumes per tile at
/// the peak of building their gather (`gather::BUILD_BYTES_PER_PRIM`).
pub const DEFAULT_GATHER_BYTES: u64 = 4 << 30;

/// Sensor paths per illuminance sensor per pass when `sensor_paths` is not given: a few
/// percent of the camera paths of a small image, enough for readings whose error falls with
/// the passes as the image's does.
pub const DEFAULT_SENSOR_PATHS: u32 = 1024;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct IntegratorDesc {
    /// Integration sphere / cylinder radius in metres, or `"auto"`: from the pixel footprint at
    /// the camera's first surface hits (`radius::auto_radius`).
    pub radius: Setting<f32>,
    /// Radius in metres for light that has scattered at least once (`radius::Radii`); absent:
    /// `radius`. Follows `radius`'s progressive schedule (the ratio stays fixed). `"auto"`:
    /// the radius or twice it, chosen by the automatic settings' pilots (`auto`), which see
    /// noise and not blur; opt-in because on spot-lit smoke and height fog the larger radius's
    /// blur is the error floor of a one-minute render (docs/performance.md).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub radius_indirect: Option<Setting<f32>>,
    /// Light tracing to the camera for the direct light of lights that are not next-event
    /// estimated, where the camera sees it on a surface (`camera_splat`): sharp and low-noise
    /// small spots (a laser's). Off: the paper's surface spheres gather it. Absent: on when
    /// next-event estimation leaves some light's direct light to forward rays
    /// (`Integrator::from_desc`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub splat_to_camera: Option<bool>,
    /// In `first-extinction` mode, camera paths always go on past a medium segment to what lies
    /// behind it (a surface, another medium), weighted by the segment's transmittance, instead
    /// of only when their walk gets through (weight 1, probability the transmittance). The
    /// segment's volumes are the walk's as before; only the surface part's indicator is
    /// replaced by its expectation, so both parts stay unbiased and the surface behind a fog
    /// loses the noise of that coin. Off: the paper's method. Absent: on with next-event
    /// estimation (`expected_transmission()`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub expected_transmission: Option<bool>,
    /// Where spheres go along a camera segment; absent: stratified with next-event estimation,
    /// the paper's walk with its pure method (`placement()`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub placement: Option<Placement>,
    /// Progressive radius reduction (Hachisuka & Jensen): R^2 shrinks by (p + alpha) / (p + 1)
    /// after pass p. Below 1 it is the schedule; 1 leaves it to `radius_schedule`.
    pub alpha: f32,
    /// The radius's schedule when `alpha` is 1; absent: consistent (`shrink()`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub radius_schedule: Option<RadiusScheduleKind>,
    /// Passes at the starting radius before the consistent schedule shrinks it.
    pub shrink_after: u64,
    /// Forward (light) rays traced per pass.
    pub forward_rays: Setting<u64>,
    /// Camera samples per pixel per pass.
    #[serde(alias = "camera_paths")]
    pub camera_samples: Setting<u32>,
    /// Longest camera or forward path in events.
    pub max_depth: u32,
    /// Multiple-spheres control parameter in (0, 1]; 1 = one sphere per camera segment.
    pub q: Setting<f32>,
    pub volume: VolumeKind,
    pub mode: GatherMode,
    pub direct: DirectMode,
    /// Distance samples of next-event estimation per camera medium segment (and light samples
    /// per diffuse surface hit).
    pub nee_samples: u32,
    /// How next-event estimation picks the light of each sample (`direct::pick`).
    pub light_pick: LightPick,
    /// Paths traced from each illuminance sensor per pass (cosine-distributed directions;
    /// `integrator::sensors`).
    pub sensor_paths: u32,
    pub channel_pick: ChannelPick,
    /// Uniform floor mixed into the channel probabilities so that none is zero.
    pub channel_floor: f32,
    pub sampler: Sampler,
    /// Upper bound on gather-structure memory per pass in bytes; 0 = `DEFAULT_GATHER_BYTES`.
    pub max_gather_bytes: u64,
    /// Passes rendered when neither `--passes` nor `--time` is given.
    pub passes: u32,
    /// Base seed of all random streams.
    pub seed: u64,
}

impl Default for IntegratorDesc {
    fn default() -> Self {
        Self {
            radius: Setting::Auto,
            radius_indirect: None,
            splat_to_camera: None,
            expected_transmission: None,
            placement: None,
            alpha: 1.0,
            radius_schedule: None,
            shrink_after: SHRINK_AFTER,
            forward_rays: Setting::Auto,
            camera_samples: Setting::Auto,
            max_depth: 32,
            q: Setting::Auto,
            volume: VolumeKind::Spheres,
            mode: GatherMode::FirstExtinction,
            direct: DirectMode::Nee,
            nee_samples: 1,
            light_pick: LightPick::Local,
            sensor_paths: DEFAULT_SENSOR_PATHS,
            channel_pick: ChannelPick::Throughput,
            channel_floor: 0.1,
            sampler: Sampler::Independent,
            max_gather_bytes: 0,
            passes: 16,
            seed: 0,
        }
    }
}

impl IntegratorDesc {
    /// The radius for scattered light the scene sets in metres (None: absent or `"auto"`).
    pub fn radius_indirect_value(&self) -> Option<f32> {
        self.radius_indirect.and_then(|r| r.value())
    }

    /// Whether the pilots choose the radius for scattered light (`radius_indirect = "auto"`).
    pub fn radius_indirect_auto(&self) -> bool {
        self.radius_indirect.is_some_and(|r| r.is_auto())
    }

    /// The radius's schedule: `alpha` below 1 is Hachisuka & Jensen's progressive rule;
    /// otherwise `radius_schedule`, consistent when absent (`radius` module comment).
    pub fn shrink(&self) -> Shrink {
        if self.alpha < 1.0 {
            return Shrink::Progressive { alpha: self.alpha };
        }
        match self
            .radius_schedule
            .unwrap_or(RadiusScheduleKind::Consistent)
        {
            RadiusScheduleKind::Fixed => Shrink::Fixed,
            RadiusScheduleKind::Consistent => Shrink::Consistent {
                after: self.shrink_after,
            },
        }
    }

    /// Whether camera paths take expected transmission (the key, or its default): on with
    /// next-event estimation, where the surfaces seen through fog are otherwise the noisiest
    /// layer (fog-cube at default settings and equal passes: 4.4x lower surface-layer and 1.7x
    /// lower whole-image standard deviation, docs/performance.md); off with the paper's pure
    /// method, whose images keep the paper's estimator.
    pub fn expected_transmission(&self) -> bool {
        self.expected_transmission.unwrap_or(match self.direct {
            DirectMode::Nee => true,
            DirectMode::Photons => false,
        })
    }

    /// Where spheres go (the key, or its default): stratified with next-event estimation,
    /// where the walk's random sphere count and positions were the largest part of a camera
    /// path's noise (fog-cube at its automatic budgets and equal passes: 1.9x lower per-pixel
    /// variance, docs/performance.md); the walk with the paper's pure method, whose images keep
    /// the paper's estimator.
    pub fn placement(&self) -> Placement {
        self.placement.unwrap_or(match self.direct {
            DirectMode::Nee => Placement::Stratified,
            DirectMode::Photons => Placement::Walk,
        })
    }

    /// The radius schedule's keys (`check`): alpha's range, a schedule named beside a
    /// progressive alpha, and the consistent schedule's wait.
    fn check_schedule(&self, fail: &mut impl FnMut(&str, String)) {
        if !(self.alpha > 0.0 && self.alpha <= 1.0) {
            fail(
                "integrator.alpha",
                format!("must be in (0, 1], got {}", self.alpha),
            );
        }
        if self.alpha < 1.0
            && let Some(kind) = self.radius_schedule
        {
            let kind = match kind {
                RadiusScheduleKind::Fixed => "fixed",
                RadiusScheduleKind::Consistent => "consistent",
            };
            fail(
                "integrator.radius_schedule",
                format!(
                    "\"{kind}\" conflicts with alpha = {} (below 1, alpha is the progressive \
                     schedule): keep one of the two",
                    self.alpha
                ),
            );
        }
        if self.shrink_after == 0 {
            fail(
                "integrator.shrink_after",
                "must be at least 1 pass (radius_schedule = \"fixed\" never shrinks)".into(),
            );
        }
    }

    /// Reports every out-of-range setting to `fail(key, message)`.
    pub fn check(&self, mut fail: impl FnMut(&str, String)) {
        if let Some(r) = self.radius.value()
            && !(r.is_finite() && r > 0.0)
        {
            fail(
                "integrator.radius",
                format!("must be a finite number > 0 or \"auto\", got {r}"),
            );
        }
        if let Some(r) = self.radius_indirect_value()
            && !(r.is_finite() && r > 0.0)
        {
            fail(
                "integrator.radius_indirect",
                format!("must be a finite number > 0 or \"auto\", got {r}"),
            );
        }
        // The pilots choose it only beside an automatic radius and automatic budgets
        // (`auto::Tuner::new`); asked for otherwise it would silently be the radius.
        if self.radius_indirect_auto()
            && (self.radius.value().is_some()
                || (self.forward_rays.value().is_some() && self.camera_samples.value().is_some()))
        {
            fail(
                "integrator.radius_indirect",
                "\"auto\" needs radius = \"auto\" and automatic forward_rays or camera_samples \
                 (the pilots that choose it run only then)"
                    .into(),
            );
        }
        self.check_schedule(&mut fail);
        if let Some(q) = self.q.value()
            && !(q > 0.0 && q <= 1.0)
        {
            fail(
                "integrator.q",
                format!("must be in (0, 1] or \"auto\", got {q}"),
            );
        }
        if let Some(n) = self.forward_rays.value()
            && !(1..=1_000_000_000_000).contains(&n)
        {
            fail(
                "integrator.forward_rays",
                format!("must be in 1..=1e12 or \"auto\", got {n}"),
            );
        }
        if let Some(n) = self.camera_samples.value()
            && !(1..=4096).contains(&n)
        {
            fail(
                "integrator.camera_samples",
                "must be in 1..=4096 or \"auto\"".into(),
            );
        }
        if !(1..=4096).contains(&self.max_depth) {
            fail("integrator.max_depth", "must be in 1..=4096".into());
        }
        if !(1..=1024).contains(&self.nee_samples) {
            fail("integrator.nee_samples", "must be in 1..=1024".into());
        }
        if !(1..=1 << 20).contains(&self.sensor_paths) {
            fail("integrator.sensor_paths", "must be in 1..=1048576".into());
        }
        if !(self.channel_floor > 0.0 && self.channel_floor <= 1.0) {
            fail("integrator.channel_floor", "must be in (0, 1]".into());
        }
        if self.passes == 0 {
            fail("integrator.passes", "must be at least 1".into());
        }
    }

    /// The gather memory budget per pass in bytes.
    pub fn gather_budget(&self) -> usize {
        let b = if self.max_gather_bytes > 0 {
            self.max_gather_bytes
        } else {
            DEFAULT_GATHER_BYTES
        };
        usize::try_from(b).unwrap_or(usize::MAX)
    }

    /// How camera segments pick their stepping bin (method note 3).
    pub fn channels(&self) -> Channels {
        Channels {
            pick: self.channel_pick,
            floor: self.channel_floor,
        }
    }
}

/// The camera side's channel-mixture rule (`channel_pick`, `channel_floor`): the camera pass
/// and truncated cylinders build the same mixture from a throughput.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Channels {
    pub pick: ChannelPick,
    pub floor: f32,
}

impl Channels {
    /// The mixture of a camera segment with throughput `w` in `medium`.
    pub fn mixture(&self, w: &Spectrum, medium: &Medium) -> Mixture {
        Mixture::new(self.pick, w, medium, self.floor)
    }
}
