use serde::{Deserialize, Serialize};

/// The integration volume camera paths leave in media (`integrator.volume`).
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

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ChannelPickDesc {
    /// P proportional to throughput times the bin's weight, with a uniform floor.
    #[default]
    Throughput,
    Uniform,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct IntegratorDesc {
    /// Integration sphere / cylinder radius in metres.
    pub radius: f32,
    /// Progressive radius reduction (Hachisuka & Jensen): R^2 shrinks by (p + alpha) / (p + 1)
    /// after pass p. 1 keeps the radius fixed (the paper's setting).
    pub alpha: f32,
    /// Forward (light) rays traced per pass.
    pub forward_rays: u64,
    /// Camera samples per pixel per pass.
    pub camera_samples: u32,
    /// Longest camera or forward path in events.
    pub max_depth: u32,
    /// Multiple-spheres control parameter in (0, 1]; 1 = one sphere per camera segment.
    pub q: f32,
    pub volume: VolumeKind,
    pub mode: GatherMode,
    pub channel_pick: ChannelPickDesc,
    /// Uniform floor mixed into the channel probabilities so that none is zero.
    pub channel_floor: f32,
    /// Upper bound on gather-structure memory per pass in bytes; 0 = a quarter of the machine's RAM.
    pub max_gather_bytes: u64,
    /// Passes rendered when neither `--passes` nor `--time` is given.
    pub passes: u32,
    /// Base seed of all random streams.
    pub seed: u64,
}

impl Default for IntegratorDesc {
    fn default() -> Self {
        Self {
            radius: 0.01,
            alpha: 1.0,
            forward_rays: 200_000,
            camera_samples: 1,
            max_depth: 32,
            q: 1.0,
            volume: VolumeKind::Spheres,
            mode: GatherMode::FirstExtinction,
            channel_pick: ChannelPickDesc::Throughput,
            channel_floor: 0.1,
            max_gather_bytes: 0,
            passes: 16,
            seed: 0,
        }
    }
}
