//! Variants (spec §7.3): the mistakes students make, and the rules that differed between
//! terms of the course, each a named deviation from one rule of spec §4-§5.
//!
//! `legacy-rt --variant ID` renders a scene *as if* with that mistake, and
//! `legacy-rt compare --diagnose` tries every variant to explain a student's image. The
//! variants cost the normal render nothing: the tracer takes a [`Rules`] type, and under
//! [`AsSpecified`] (every render without a variant) each `V::DEVIATES && …` test is false
//! at compile time, so the deviating code is not in the normal render at all. Variants of
//! the scene's geometry (cone-scale, tile-parity, no-z-rule) rewrite a copy of the scene
//! instead ([`Deviations::scene`]); nearer-root reads the shape's own account of its
//! roots (`FirstRoot`); max-dist=D and the kernels are options the renderer already
//! has.

use crate::render::{DEFAULT_MAX_DIST, Options, to_byte};
use crate::scene::{Pattern, Scene};
use crate::shapes::kernel::KernelChoice;
use crate::shapes::{Cone, HitNote, Notes, Shape, Verdict};
use std::borrow::Cow;

/// The ε of `shadow-epsilon` unless another is given (`shadow-epsilon=1e-3`).
pub const DEFAULT_EPSILON: f64 = 1e-6;

/// One deviation from spec §4-§5, as `--variant` names it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Variant {
    /// §4.1: the world point at (x + 0.5)/W instead of x/(W - 1).
    PixelCentre,
    /// §4.1: output row r holds y = r (bottom row first).
    UpsideDown,
    /// §4.7: bytes rounded half up instead of truncated.
    RoundBytes,
    /// §4.7: trunc(256 c) clamped to 255 instead of trunc(255 c).
    Scale256,
    /// §4.2 step 6: no division by the distance.
    NoDistance,
    /// §4.2 step 6: divided by this segment's length, not the path's.
    SegmentDistance,
    /// §4.3: cos θ / dist² instead of cos θ / dist.
    SquareFalloff,
    /// §4.3: no shadow rays (every light reaches), mirrors still reflect.
    NoShadows,
    /// §4.2/§4.3: rays leaving a surface test every object and count hits with t > ε,
    /// instead of skipping the object they leave.
    ShadowEpsilon(f64),
    /// §4.4: the normal flipped toward the viewer (N·D > 0 → -N).
    FacingNormals,
    /// §5.1: no miss for plane hits with z > 0.
    NoZRule,
    /// §5.4: even relx + rely → foreground.
    TileParity,
    /// §5.6: the cone's k = r²/h (the paraboloid's) instead of (r/h)².
    ConeScale,
    /// §5.6: the quadrics 21-24 try only the smaller root; out of bounds is a miss.
    NearerRoot,
    /// §4.5: at most one reflected ray per camera ray.
    OneBounce,
    /// §4.2: MAX_DIST D instead of 32.
    MaxDist(f64),
    /// The notes' root formula in f64 or f32 (`--kernel textbook`, `textbook-f32`).
    Kernel(KernelChoice),
}

/// What a variant deviates from, for `--help`, the docs and the report.
pub struct About {
    /// The id `--variant` takes (`max-dist=D` for [`Variant::MaxDist`]).
    pub id: &'static str,
    /// The spec's rule it replaces.
    pub rule: &'static str,
    /// What it does instead.
    pub instead: &'static str,
}

impl Variant {
    /// Every variant `compare --diagnose` tries on its own, in the order of spec §7.3;
    /// max-dist=D is estimated separately.
    pub const TRIED: [Variant; 17] = [
        Variant::PixelCentre,
        Variant::UpsideDown,
        Variant::RoundBytes,
        Variant::Scale256,
        Variant::NoDistance,
        Variant::SegmentDistance,
        Variant::SquareFalloff,
        Variant::NoShadows,
        Variant::ShadowEpsilon(DEFAULT_EPSILON),
        Variant::FacingNormals,
        Variant::NoZRule,
        Variant::TileParity,
        Variant::ConeScale,
        Variant::NearerRoot,
        Variant::OneBounce,
        Variant::Kernel(KernelChoice::Textbook),
        Variant::Kernel(KernelChoice::TextbookF32),
    ];

    /// Every variant with its rule, in the order of spec §7.3 (max-dist=D with D = 70,
    /// the other term's value).
    pub fn all() -> impl Iterator<Item = Variant> {
        let max_dist = Variant::MaxDist(70.0);
        Variant::TRIED[..15]
            .iter()
            .copied()
            .chain([max_dist])
            .chain(Variant::TRIED[15..].iter().copied())
    }

    /// The id, with its value where it has one: `max-dist=70`, `shadow-epsilon=0.001`
    /// (plain `shadow-epsilon` for ε = 1e-6).
    pub fn id(self) -> String {
        match self {
            Variant::MaxDist(d) => format!("max-dist={d}"),
            Variant::ShadowEpsilon(e) if e != DEFAULT_EPSILON => format!("shadow-epsilon={e}"),
            _ => self.about().id.to_string(),
        }
    }

    /// The variant named `text`: an id, or `max-dist=D`, or `shadow-epsilon=E`.
    pub fn parse(text: &str) -> Result<Variant, String> {
        let value = |name: &str, value: &str| -> Result<f64, String> {
            match value.parse::<f64>() {
                Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
                _ => Err(format!(
                    "{name}= takes a number greater than 0, found {value:?}"
                )),
            }
        };
        if let Some(d) = text.strip_prefix("max-dist=") {
            return Ok(Variant::MaxDist(value("max-dist", d)?));
        }
        if let Some(e) = text.strip_prefix("shadow-epsilon=") {
            return Ok(Variant::ShadowEpsilon(value("shadow-epsilon", e)?));
        }
        if text == "max-dist" {
            return Err("max-dist takes its distance: max-dist=70".to_string());
        }
        Variant::all()
            .find(|v| !matches!(v, Variant::MaxDist(_)) && v.about().id == text)
            .ok_or_else(|| {
                let ids: Vec<_> = Variant::all().map(|v| v.about().id).collect();
                format!(
                    "unknown variant {text:?}; the variants are: {}",
                    ids.join(", ")
                )
            })
    }

    /// The rule it replaces and what it does instead (spec §7.3).
    pub fn about(self) -> About {
        let (id, rule, instead) = match self {
            Variant::PixelCentre => (
                "pixel-centre",
                "§4.1 world point x/(W-1)·ww - ww/2",
                "(x + 0.5)/W·ww - ww/2, and the same for y",
            ),
            Variant::UpsideDown => (
                "upside-down",
                "§4.1 output row r holds y = H-1-r",
                "row r holds y = r: the image upside down",
            ),
            Variant::RoundBytes => (
                "round-bytes",
                "§4.7 bytes truncated",
                "rounded half up: floor(255·c + 0.5)",
            ),
            Variant::Scale256 => ("scale-256", "§4.7 ×255", "trunc(256·c), clamped to 255"),
            Variant::NoDistance => (
                "no-distance",
                "§4.2 step 6 I = I / total_dist",
                "no division",
            ),
            Variant::SegmentDistance => (
                "segment-distance",
                "§4.2 step 6 divides by the cumulative distance",
                "divides by the distance from this segment's base to the hit",
            ),
            Variant::SquareFalloff => ("square-falloff", "§4.3 cos θ / dist", "cos θ / dist²"),
            Variant::NoShadows => (
                "no-shadows",
                "§4.3 shadow ray",
                "every light reaches (stage diffuse, but with reflection)",
            ),
            Variant::ShadowEpsilon(_) => (
                "shadow-epsilon",
                "§4.2/§4.3 shadow and reflected rays skip the object they leave",
                "they test every object, counting hits with t > ε only \
                 (ε = 1e-6, or shadow-epsilon=E)",
            ),
            Variant::FacingNormals => (
                "facing-normals",
                "§4.4 normals never flipped",
                "N flipped when N·D > 0",
            ),
            Variant::NoZRule => ("no-z-rule", "§5.1 miss if z > 0", "no z test"),
            Variant::TileParity => (
                "tile-parity",
                "§5.4 odd relx + rely → foreground",
                "even → foreground",
            ),
            Variant::ConeScale => (
                "cone-scale",
                "§3.2/§5.6 cone k = (r/h)²",
                "k = r²/h (the paraboloid's formula)",
            ),
            Variant::NearerRoot => (
                "nearer-root",
                "§5.6 smallest positive root in bounds",
                "only the smaller root is tried; out of bounds is a miss",
            ),
            Variant::OneBounce => (
                "one-bounce",
                "§4.5 recursion",
                "at most one reflected ray per camera ray",
            ),
            Variant::MaxDist(_) => (
                "max-dist=D",
                "§4.2 MAX_DIST 32",
                "MAX_DIST D (one term of the course used 70)",
            ),
            Variant::Kernel(KernelChoice::TextbookF32) => (
                "textbook-f32",
                "the accurate roots",
                "the notes' (-b ± sqrt(b² - 4ac)) / 2a in f32",
            ),
            Variant::Kernel(KernelChoice::Stable) => (
                "stable",
                "the accurate roots",
                "the notes' coefficients with cancellation-free roots",
            ),
            Variant::Kernel(_) => (
                "textbook",
                "the accurate roots",
                "the notes' (-b ± sqrt(b² - 4ac)) / 2a in f64",
            ),
        };
        About { id, rule, instead }
    }
}

impl Variant {
    /// "what it does instead of the rule it replaces", with the variant's value.
    pub fn describe(self) -> String {
        let about = self.about();
        let instead = match self {
            Variant::MaxDist(d) => format!("MAX_DIST {d}"),
            Variant::ShadowEpsilon(e) => {
                format!("rays leaving a surface test every object, counting hits with t > {e} only")
            }
            _ => about.instead.to_string(),
        };
        format!("{instead}, instead of {}", about.rule)
    }
}

/// How a channel becomes a byte (spec §4.7 or a variant of it).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Bytes {
    /// Clamp, ×255, truncate (spec §4.7).
    #[default]
    Truncate,
    /// round-bytes.
    Round,
    /// scale-256.
    Scale256,
}

impl Bytes {
    /// The byte of `channel` under this rule. NaN gives 0.
    #[inline]
    pub fn byte(self, channel: f64) -> u8 {
        match self {
            Bytes::Truncate => to_byte(channel),
            _ if channel.is_nan() => 0,
            Bytes::Round => (channel.clamp(0.0, 1.0) * 255.0 + 0.5).floor() as u8,
            Bytes::Scale256 => (channel.clamp(0.0, 1.0) * 256.0).min(255.0) as u8,
        }
    }
}

/// What step 6 of spec §4.2 divides by.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Divisor {
    /// The path's cumulative length (spec §4.2).
    #[default]
    Path,
    /// no-distance.
    Nothing,
    /// segment-distance.
    Segment,
}

/// The deviations a render applies: none, for the image of spec §4-§5.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Deviations {
    /// pixel-centre.
    pub pixel_centre: bool,
    /// upside-down.
    pub upside_down: bool,
    /// round-bytes or scale-256.
    pub bytes: Bytes,
    /// no-distance or segment-distance.
    pub divisor: Divisor,
    /// square-falloff.
    pub square_falloff: bool,
    /// no-shadows.
    pub no_shadows: bool,
    /// shadow-epsilon's ε.
    pub epsilon: Option<f64>,
    /// facing-normals.
    pub facing_normals: bool,
    /// no-z-rule.
    pub no_z_rule: bool,
    /// tile-parity.
    pub tile_parity: bool,
    /// cone-scale.
    pub cone_scale: bool,
    /// nearer-root.
    pub nearer_root: bool,
    /// one-bounce.
    pub one_bounce: bool,
}

impl Deviations {
    /// Whether any rule of the tracer deviates: every variant but those of the camera
    /// (pixel-centre) and of the scene's geometry ([`Deviations::scene`]), which need no
    /// deviating tracer.
    pub fn in_tracer(&self) -> bool {
        let Deviations {
            pixel_centre: _,
            no_z_rule: _,
            tile_parity: _,
            cone_scale: _,
            upside_down,
            nearer_root,
            bytes,
            divisor,
            square_falloff,
            no_shadows,
            epsilon,
            facing_normals,
            one_bounce,
        } = *self;
        upside_down
            || bytes != Bytes::Truncate
            || divisor != Divisor::Path
            || square_falloff
            || no_shadows
            || epsilon.is_some()
            || facing_normals
            || nearer_root
            || one_bounce
    }

    /// The variants these deviations apply, in the order of spec §7.3.
    pub fn variants(&self) -> Vec<Variant> {
        let d = *self;
        let divisor = match d.divisor {
            Divisor::Path => None,
            Divisor::Nothing => Some(Variant::NoDistance),
            Divisor::Segment => Some(Variant::SegmentDistance),
        };
        let bytes = match d.bytes {
            Bytes::Truncate => None,
            Bytes::Round => Some(Variant::RoundBytes),
            Bytes::Scale256 => Some(Variant::Scale256),
        };
        [
            d.pixel_centre.then_some(Variant::PixelCentre),
            d.upside_down.then_some(Variant::UpsideDown),
            bytes,
            divisor,
            d.square_falloff.then_some(Variant::SquareFalloff),
            d.no_shadows.then_some(Variant::NoShadows),
            d.epsilon.map(Variant::ShadowEpsilon),
            d.facing_normals.then_some(Variant::FacingNormals),
            d.no_z_rule.then_some(Variant::NoZRule),
            d.tile_parity.then_some(Variant::TileParity),
            d.cone_scale.then_some(Variant::ConeScale),
            d.nearer_root.then_some(Variant::NearerRoot),
            d.one_bounce.then_some(Variant::OneBounce),
        ]
        .into_iter()
        .flatten()
        .collect()
    }

    /// The scene as the variants of its geometry change it: borrowed unchanged when none
    /// applies.
    pub fn scene<'a>(&self, scene: &'a Scene) -> Cow<'a, Scene> {
        if !(self.no_z_rule || self.tile_parity || self.cone_scale) {
            return Cow::Borrowed(scene);
        }
        let mut scene = scene.clone();
        for object in &mut scene.objects {
            if self.tile_parity
                && let Pattern::Tiles { background, .. } = &mut object.pattern
            {
                // Even relx + rely now picks the first material: the same as swapping the
                // two materials under the odd rule.
                std::mem::swap(&mut object.material, background);
            }
            let shape = &mut object.shape;
            if self.cone_scale
                && let Shape::Cone(cone) = shape
            {
                let size = cone.size;
                *cone = Cone::with_k(
                    cone.equation.frame.clone(),
                    size,
                    size.radius.powi(2) / size.height,
                );
            }
            if self.no_z_rule
                && let Some(plane) = shape.plane_mut()
            {
                plane.z_rule = false;
            }
        }
        Cow::Owned(scene)
    }
}

/// The variant nearer-root from a quadric 21-24's own notes: its smaller root counts if
/// the shape accepted it, and no other root is tried (spec §7.3).
#[derive(Debug, Default)]
pub(crate) struct FirstRoot(Option<Option<f64>>);

impl FirstRoot {
    /// The smaller root's t if it counted.
    pub(crate) fn t(&self) -> Option<f64> {
        self.0.flatten()
    }

    /// The same from notes already taken: the first root's t if it counted. The notes
    /// after that root are dropped (the variant never computes them).
    pub(crate) fn of(notes: &mut Vec<HitNote>) -> Option<f64> {
        let mut first = FirstRoot::default();
        let end = notes.iter().position(|&note| {
            first.note(note);
            first.0.is_some()
        });
        notes.truncate(end.map_or(notes.len(), |end| end + 1));
        first.t()
    }
}

impl Notes for FirstRoot {
    #[inline]
    fn note(&mut self, note: HitNote) {
        if let (None, HitNote::Root { t, verdict, .. }) = (self.0, note) {
            self.0 = Some((verdict == Verdict::Counts).then_some(t));
        }
    }
}

/// A rule that two variants both replace: they cannot apply together.
#[derive(Debug, Clone, PartialEq)]
pub struct Conflict {
    /// The variant given first.
    pub first: String,
    /// The one that replaces the same rule.
    pub second: String,
}

impl std::fmt::Display for Conflict {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the variants {} and {} replace the same rule: give one of them",
            self.first, self.second
        )
    }
}

impl Options {
    /// These options with `variant` applied; an error when a variant already applied
    /// replaces the same rule (two byte rules, two divisors, two kernels, two MAX_DISTs).
    pub fn with_variant(&self, variant: Variant) -> Result<Options, Conflict> {
        let mut options = *self;
        let d = &mut options.deviations;
        let taken = |before: Option<Variant>| -> Result<(), Conflict> {
            match before {
                Some(first) => Err(Conflict {
                    first: first.id(),
                    second: variant.id(),
                }),
                None => Ok(()),
            }
        };
        match variant {
            Variant::PixelCentre => d.pixel_centre = true,
            Variant::UpsideDown => d.upside_down = true,
            Variant::RoundBytes | Variant::Scale256 => {
                taken(match d.bytes {
                    Bytes::Truncate => None,
                    Bytes::Round => Some(Variant::RoundBytes),
                    Bytes::Scale256 => Some(Variant::Scale256),
                })?;
                d.bytes = match variant {
                    Variant::RoundBytes => Bytes::Round,
                    _ => Bytes::Scale256,
                };
            }
            Variant::NoDistance | Variant::SegmentDistance => {
                taken(match d.divisor {
                    Divisor::Path => None,
                    Divisor::Nothing => Some(Variant::NoDistance),
                    Divisor::Segment => Some(Variant::SegmentDistance),
                })?;
                d.divisor = match variant {
                    Variant::NoDistance => Divisor::Nothing,
                    _ => Divisor::Segment,
                };
            }
            Variant::SquareFalloff => d.square_falloff = true,
            Variant::NoShadows => d.no_shadows = true,
            Variant::ShadowEpsilon(e) => {
                taken(d.epsilon.map(Variant::ShadowEpsilon))?;
                d.epsilon = Some(e);
            }
            Variant::FacingNormals => d.facing_normals = true,
            Variant::NoZRule => d.no_z_rule = true,
            Variant::TileParity => d.tile_parity = true,
            Variant::ConeScale => d.cone_scale = true,
            Variant::NearerRoot => d.nearer_root = true,
            Variant::OneBounce => d.one_bounce = true,
            Variant::MaxDist(dist) => {
                let before = self.max_dist != DEFAULT_MAX_DIST;
                taken(before.then_some(Variant::MaxDist(self.max_dist)))?;
                options.max_dist = dist;
            }
            Variant::Kernel(kernel) => {
                let before = self.kernel != KernelChoice::Accurate;
                taken(before.then_some(Variant::Kernel(self.kernel)))?;
                options.kernel = kernel;
            }
        }
        Ok(options)
    }

    /// The output row that holds pixel row `y` (0 at the bottom): H - 1 - y (spec §4.1),
    /// or y under upside-down. The map is its own inverse: it also gives the pixel row
    /// that output row `y` holds.
    pub fn row_of(&self, y: usize) -> usize {
        if self.deviations.upside_down {
            y
        } else {
            self.height - 1 - y
        }
    }
}

/// Whether the tracer applies [`Deviations`]: a type, so that a render without variants
/// compiles without them.
pub trait Rules: Send + Sync + 'static {
    /// False for the image of spec §4-§5: every deviation's test is then false at
    /// compile time.
    const DEVIATES: bool;
}

/// The rules of spec §4-§5, as written.
pub struct AsSpecified;

impl Rules for AsSpecified {
    const DEVIATES: bool = false;
}

/// The rules with [`Options::deviations`] applied.
pub struct Deviating;

impl Rules for Deviating {
    const DEVIATES: bool = true;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_id_parses_back_to_its_variant() {
        for variant in Variant::all() {
            assert_eq!(Variant::parse(&variant.id()), Ok(variant));
        }
        let epsilon = Variant::ShadowEpsilon(1e-3);
        assert_eq!(Variant::parse("shadow-epsilon=0.001"), Ok(epsilon));
        assert!(Variant::parse("max-dist").is_err());
        assert!(Variant::parse("max-dist=-4").is_err());
        assert!(
            Variant::parse("upside")
                .unwrap_err()
                .contains("pixel-centre")
        );
    }

    #[test]
    fn byte_rules_follow_their_formulas() {
        // 0.5: 127.5 truncates to 127, rounds to 128; 256 × 0.5 = 128.
        let half = [Bytes::Truncate, Bytes::Round, Bytes::Scale256].map(|b| b.byte(0.5));
        assert_eq!(half, [127, 128, 128]);
        // 0.999: 254.745 → 254 and 255; 255.744 → 255.
        let high = [Bytes::Truncate, Bytes::Round, Bytes::Scale256].map(|b| b.byte(0.999));
        assert_eq!(high, [254, 255, 255]);
        assert_eq!(Bytes::Scale256.byte(1.0), 255); // 256 clamped
        assert_eq!(Bytes::Round.byte(f64::NAN), 0);
    }

    #[test]
    fn deviations_name_the_variants_that_made_them() {
        let mut options = Options::new(4, 3);
        for variant in Variant::TRIED {
            if let Variant::Kernel(_) = variant {
                continue;
            }
            options = options.with_variant(variant).unwrap_or(options);
        }
        let ids: Vec<_> = options
            .deviations
            .variants()
            .iter()
            .map(|v| v.id())
            .collect();
        let expected = [
            "pixel-centre",
            "upside-down",
            "round-bytes",
            "no-distance",
            "square-falloff",
            "no-shadows",
            "shadow-epsilon",
            "facing-normals",
            "no-z-rule",
            "tile-parity",
            "cone-scale",
            "nearer-root",
            "one-bounce",
        ];
        assert_eq!(ids, expected);
    }

    #[test]
    fn two_variants_of_one_rule_conflict() {
        let options = Options::new(4, 3)
            .with_variant(Variant::RoundBytes)
            .unwrap();
        assert!(options.with_variant(Variant::Scale256).is_err());
        assert!(options.with_variant(Variant::NoDistance).is_ok());
        let far = options.with_variant(Variant::MaxDist(70.0)).unwrap();
        assert_eq!(far.max_dist, 70.0);
        assert!(far.with_variant(Variant::MaxDist(50.0)).is_err());
    }
}
