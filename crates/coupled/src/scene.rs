//! A validated scene in SI units: the plate, the bodies, the support sets, the impact points,
//! the velocities and what to compute. Reading and checking scene files is the command
//! line's business; this type only holds what passed.

use crate::reduced::SignalSettings;
use crate::supports::SupportSet;
use crate::transient::{Discretisation, LawKind};
use analytic::{Method, Plate, Sphere};
use serde::{Deserialize, Serialize};

/// Declares [`Analysis`], one line per analysis: its doc, its variant and its key in scene
/// files (the order is the order reports present them).
macro_rules! analyses {
    ($($(#[doc = $doc:literal])* $variant:ident => $key:literal,)*) => {
        /// What a scene asks for. Nothing that is not asked for is assembled, factorized,
        /// simulated or written.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Deserialize, Serialize)]
        pub enum Analysis {
            $($(#[doc = $doc])* #[serde(rename = $key)] $variant,)*
        }

        impl Analysis {
            /// Every analysis, in the order reports present them.
            pub const ALL: &'static [Analysis] = &[$(Analysis::$variant),*];

            /// The name used in scene files.
            pub fn key(self) -> &'static str {
                match self {
                    $(Analysis::$variant => $key,)*
                }
            }
        }
    };
}

analyses! {
    /// Responses at maximum compression for every velocity.
    Responses => "responses",
    /// Yield velocities (eqs. 51-54).
    YieldVelocity => "yield-velocity",
    /// Beam against plate over the whole plate (x along the length, z across the width).
    WidthMaps => "width-maps",
    /// Plate against beam at the centre as the width-to-length ratio B/L changes.
    AspectRatio => "aspect-ratio",
    /// Accuracy of the plate compliance against computing time, per mesh.
    ErrorVsTime => "error-vs-time",
    /// Both models at extreme compliances, velocities and moduli.
    ExtremeCases => "extreme-cases",
    /// The Reissner-Mindlin plate (transverse shear) against Kirchhoff's at the scene's points.
    TransverseShear => "transverse-shear",
    /// The scene's bodies and velocities on a box-section tail beam (`[tail_beam]`, flat shell
    /// elements) beside the paper's beam and Kirchhoff plate.
    TailBeam => "tail-beam",
    /// The scene's bodies and velocities on a shell structure read from a mesh file
    /// (`[shell_mesh]`: Gmsh's MSH with named groups), its compliance on a ladder of the
    /// file's mesh and its refinements.
    ShellMesh => "shell-mesh",
    /// The plate FE and transient models against their classical references.
    Verification => "verification",
    /// Transient against quasi-static at the scene's points.
    Transient => "transient",
    /// The transient study's contact laws side by side (Hertz, Flores, Thornton) at multiples
    /// of the yield velocity: twelve transient runs with error estimates, written only when
    /// asked for.
    ContactLaws => "contact-laws",
    /// The quasi-static error of the transient model over plate size and thickness.
    SizeMap => "size-map",
    /// The regime maps: the quasi-static error over plate size, thickness, sphere mass and
    /// spring stiffness for Con 1-3, beside Olsson's and Christoforou and Yigit's criteria
    /// and the closed-form rule.
    RegimeMaps => "regime-maps",
    /// The paper's own studies: its conclusions item by item and its figures redone with
    /// both models (the paper's plate only).
    PaperStudies => "paper-studies",
    /// Coal-gangue identification over the scene's random-impact ensemble (`[ensemble]`).
    Identify => "identify",
    /// Recorded drop tests against the model (`impact drops --signal`): the scene gives the
    /// plate, the support sets, the sensors and the measurement chain; the drops come with
    /// the recording.
    Drops => "drops",
}

/// Impact points, (x, z) in m: x from the left end in [0, L], z from the near edge in [0, B].
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "layout", rename_all = "kebab-case")]
pub enum Points {
    /// Explicit (x, z) pairs, in the order given.
    Pairs {
        /// (x, z) in m.
        pairs: Vec<(f64, f64)>,
    },
    /// Every x with every z, x outermost.
    Grid {
        /// Positions along the length, m.
        x: Vec<f64>,
        /// Positions across the width, m.
        z: Vec<f64>,
    },
}

impl Points {
    /// The points as (x, z) pairs (a grid x-major).
    pub fn pairs(&self) -> Vec<(f64, f64)> {
        match self {
            Points::Pairs { pairs } => pairs.clone(),
            Points::Grid { x, z } => x.iter().flat_map(|&x| z.iter().map(move |&z| (x, z))).collect(),
        }
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        match self {
            Points::Pairs { pairs } => pairs.len(),
            Points::Grid { x, z } => x.len() * z.len(),
        }
    }

    /// Whether there are none (a validated scene always has some).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// `count` points evenly spaced along the centreline z = `width`/2 of a plate of `length`.
    pub fn centreline(length: f64, width: f64, count: usize) -> Self {
        Points::Pairs { pairs: even_points(length, count).into_iter().map(|x| (x, width / 2.0)).collect() }
    }
}

/// `count` points from 0 to `length` inclusive; the ends are exact.
pub fn even_points(length: f64, count: usize) -> Vec<f64> {
    (0..count).map(|i| if i + 1 == count { length } else { length * i as f64 / (count - 1) as f64 }).collect()
}

/// Another plate for the stream study's transfer: the scene's plate with some of its size and
/// material changed, struck by the same lumps (the same uniforms) in `region`, with the same
/// supports, sensor points and chain.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OtherPlate {
    /// The shift in words, from the keys the scene changes ("plate 12 mm thick").
    pub shift: String,
    /// The plate.
    pub plate: Plate,
    /// Where its lumps strike: the scene's `[ensemble.region]` where one is given, else this
    /// whole plate (the lumps' uniforms mapped onto it).
    pub region: identify::ensemble::Region,
}

/// A validated scene in SI units.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Scene {
    /// Short name, used in titles.
    pub name: String,
    /// One line on what the scene is.
    pub description: String,
    /// The plate.
    pub plate: Plate,
    /// The striking spheres, names unique.
    pub bodies: Vec<Sphere>,
    /// Restitution e of the Flores law (eq. 1).
    pub restitution: f64,
    /// The transient model's contact law (the quasi-static model is the paper's Flores law).
    pub contact_law: LawKind,
    /// Gravity on the sphere toward the plate, m/s², in the transient and reduced models
    /// ([`crate::transient::Striker::gravity`]); 0 in the paper's impact.
    pub gravity: f64,
    /// The plate's Rayleigh damping, the same in the transient (C = αM + βK) and the reduced
    /// model (ζᵢ = α/(2ωᵢ) + βωᵢ/2 on each mode); None: the transient plate is undamped (the
    /// paper's) and the reduced model keeps `[signals]`'s modal damping ratio.
    pub plate_damping: Option<plate_fem::dynamics::Rayleigh>,
    /// Support sets, names unique.
    pub conditions: Vec<SupportSet>,
    /// Impact points.
    pub points: Points,
    /// Impact points of the transient study (`impact dynamic`): each is a time integration,
    /// so a scene may name fewer than its points; by default the same points.
    pub transient_points: Vec<(f64, f64)>,
    /// m/s; empty only when no analysis needs velocities.
    pub velocities: Vec<f64>,
    /// What to compute.
    pub analyses: Vec<Analysis>,
    /// How to solve the energy balance.
    pub solver: Method,
    /// The random-impact ensemble of the identification study; present exactly when the
    /// scene asks for [`Analysis::Identify`].
    pub ensemble: Option<identify::Study>,
    /// The reduced model and the sensor signals of an impact (`[signals]`; defaults when
    /// the scene has none).
    pub signals: SignalSettings,
    /// The measurement chain between the reduced model's signals and the identification's
    /// features (`[measurement]`); None: the features read the model's signals as they are.
    /// Left out of the serialised scene when None, so that a scene without a chain keeps the
    /// canonical content (and provenance hash) it had before chains existed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub measurement: Option<identify::measurement::ChainSpec>,
    /// The caving-stream detection study (`[stream]`) on the ensemble's lumps; None: none.
    /// Left out of the serialised scene when None, as `measurement` is.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stream: Option<identify::stream::StreamStudy>,
    /// The contact laws `[stream] law_sweep` runs the stream study's streams with besides
    /// `contact_law`, each a whole set of streams to which each support set's detector is
    /// carried. Left out of the serialised scene when empty.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub stream_law_sweep: Vec<LawKind>,
    /// The other plates `[stream] plate_sweep` runs the stream study's streams on, each a
    /// whole set of streams to which each support set's detector is carried. Left out of the
    /// serialised scene when empty.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub stream_plate_sweep: Vec<OtherPlate>,
    /// How the transient model is discretised: by default each case's mesh and step are
    /// chosen so that its error estimate is within 1e-4 of P_max and the contact time.
    pub transient_discretisation: Discretisation,
    /// The share of m·v₀ a contact's impulse must reach to count as one of the impact's main
    /// contacts; the others are micro-contacts (chatter), counted with their total impulse
    /// ([`crate::transient::chatter`]).
    pub main_contact_share: f64,
    /// The tail beam (`[tail_beam]`); present exactly when the scene asks for
    /// [`Analysis::TailBeam`]. Left out of the serialised scene when None.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tail_beam: Option<crate::compliance::tail_beam::TailBeamScene>,
    /// The structure read from a mesh file (`[shell_mesh]`); present exactly when the scene
    /// asks for [`Analysis::ShellMesh`]. Left out of the serialised scene when None.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shell_mesh: Option<crate::compliance::shell_mesh::ShellMeshScene>,
}

impl Scene {
    /// Where the transient model's discretisation starts ([`Discretisation::start`]), with the
    /// scene's plate damping.
    pub fn transient_start(&self) -> crate::transient::TransientSettings {
        crate::transient::TransientSettings { damping: self.plate_damping, ..self.transient_discretisation.start() }
    }

    /// Whether the scene asks for `analysis`.
    pub fn wants(&self, analysis: Analysis) -> bool {
        self.analyses.contains(&analysis)
    }

    /// Whether its identification strikes its tail beam: a scene with a [`crate::compliance::tail_beam::TailBeamScene`] that
    /// asks for identification, whose lumps' region and sensors lie on the box's top face.
    pub fn identifies_on_tail_beam(&self) -> bool {
        self.tail_beam.is_some() && self.wants(Analysis::Identify)
    }

    /// A copy whose points are `count` evenly spaced positions on the centreline (the paper
    /// divides L into 100 parts: 101 points).
    pub fn with_sweep(&self, count: usize) -> Self {
        let mut s = self.clone();
        s.points = Points::centreline(self.plate.length(), self.plate.width(), count);
        s
    }

    /// The impact points as (x, z) pairs.
    pub fn point_pairs(&self) -> Vec<(f64, f64)> {
        self.points.pairs()
    }
}
