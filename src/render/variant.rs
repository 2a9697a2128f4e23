//! Variants (spec §7.3, §7.4): the mistakes students make, and the rules that differed
//! between terms of the course, each a named replacement of one rule of spec §4-§5.
//!
//! They are one table, [`VARIANTS`]: a row per variant with its id, the rule it replaces,
//! what it does instead, where its rule lives ([`Site`]), its parameter and what it may be
//! scoped to (`ID@LINE`, [`Scope`]). `--help`, docs/variants.md's list, the page's
//! vocabulary and what `compare --diagnose` tries are made from it; adding a variant is a
//! row here and its rule at its site. A render turns the variants it is given into
//! `Rules`, the values the tracer consults where each rule lives, and into a copy of the
//! scene for the rules that live in the scene's geometry (`Rules::scene`).

use crate::render::{DEFAULT_MAX_DIST, Options, to_byte};
use crate::scene::{Pattern, Scene};
use crate::shapes::kernel::KernelChoice;
use crate::shapes::{Cone, Shape};
use glam::DVec3;
use std::borrow::Cow;
use std::sync::Arc;

/// The ε of `shadow-epsilon` unless another is given (`shadow-epsilon=1e-3`).
pub const DEFAULT_EPSILON: f64 = 1e-6;

/// Why render choices cannot go together, or cannot apply to a scene. None of the
/// messages starts with `error: `, which the command line adds.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ChoiceError {
    /// `--max-dist` is not a positive number.
    #[error("--max-dist must be greater than 0, found {0}")]
    MaxDist(f64),
    /// Two variants replace the same rule for the same records.
    #[error("the variants {first} and {second} replace the same rule: give one of them")]
    Conflict {
        /// The variant given first, as its id (or the kernel's name).
        first: String,
        /// The one given second.
        second: String,
    },
    /// More variants than a render holds.
    #[error("at most {0} variants apply at once")]
    TooMany(usize),
    /// A scoped variant names a line that starts no record of the kinds it applies to.
    #[error("--variant {id}: {there}; {applies} applies to {kinds}, and {lines}")]
    Scope {
        /// The variant as given (`cone-scale@3`).
        id: String,
        /// What starts on its line, if anything ("line 3 starts a sphere").
        there: String,
        /// The variant's id without scope.
        applies: &'static str,
        /// The kinds of record it applies to, plural.
        kinds: &'static str,
        /// The lines that would do, or that the scene has none.
        lines: String,
    },
}

/// Where a variant's rule lives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Site {
    /// The camera: where the rays go and where the pixels land (spec §4.1).
    Camera,
    /// The scene's geometry or materials, changed in a copy before the render.
    Scene,
    /// Which hits count: the aggregate's closest hit and shadow test (spec §4.3, §4.6).
    Hits,
    /// The tracer's loop: lights, normals, the division, the mirror (spec §4.2-§4.5).
    Tracer,
    /// The conversion of a colour to bytes (spec §4.7).
    Bytes,
    /// A render option: MAX_DIST or the kernel.
    Option,
}

/// The kinds of object a variant scoped to one record applies to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kinds {
    /// Any kind of object.
    Any,
    /// Cones (type 23), whose k the variant cone-scale replaces.
    Cones,
    /// The plane-based objects (14-17, 20), whose hits have a z rule.
    Planes,
    /// Tiled planes (16).
    TiledPlanes,
    /// The planes with a frame: finite, tiled and textured (15-17).
    FramedPlanes,
    /// The quadrics 21-24, whose roots are chosen within bounds.
    BoundedQuadrics,
}

impl Kinds {
    /// Whether `shape` is of these kinds.
    pub(crate) fn admit(self, shape: &Shape) -> bool {
        match self {
            Kinds::Any => true,
            Kinds::Cones => matches!(shape, Shape::Cone(_)),
            Kinds::Planes => shape.plane().is_some(),
            Kinds::TiledPlanes => matches!(shape, Shape::TiledPlane(_)),
            Kinds::FramedPlanes => matches!(shape, Shape::TiledPlane(_) | Shape::FinitePlane(_)),
            Kinds::BoundedQuadrics => shape.axis_frame().is_some(),
        }
    }

    /// The kinds in words, plural.
    fn name(self) -> &'static str {
        match self {
            Kinds::Any => "objects",
            Kinds::Cones => "cones (23)",
            Kinds::Planes => "plane-based objects (14-17, 20)",
            Kinds::TiledPlanes => "tiled planes (16)",
            Kinds::FramedPlanes => "finite, tiled and textured planes (15-17)",
            Kinds::BoundedQuadrics => "quadrics 21-24",
        }
    }
}

/// What a variant applies to: the whole image, or (`ID@LINE`) the one record whose type
/// code is on LINE.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scope {
    /// The whole image only.
    Image,
    /// The whole image, or one object of these kinds.
    ImageOrObject(Kinds),
    /// One object of these kinds only: the edits of spec §7.4.
    Object(Kinds),
    /// The whole image, or one light.
    ImageOrLight,
    /// One light only.
    Light,
    /// One record, object or light: where the reader stopped (stopped-at@LINE).
    Record,
}

/// The parameter a variant takes after `=`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Parameter {
    /// It takes no parameter.
    None,
    /// A required number greater than 0, named as in the id (`max-dist=D`), and the value
    /// `compare --diagnose` tries first.
    Required(&'static str, f64),
    /// A number greater than 0 with a default (`shadow-epsilon[=E]`).
    Optional(&'static str, f64),
    /// A required whole number other than 0, of either sign (`row-offset=N`), and the
    /// value tried first.
    Integer(&'static str, f64),
}

/// A row of the table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Row {
    /// The variant this row describes.
    pub kind: Kind,
    /// The id `--variant` takes.
    pub id: &'static str,
    /// Where its rule lives.
    pub site: Site,
    /// What it may be scoped to.
    pub scope: Scope,
    /// The value it takes after `=`, if any.
    pub parameter: Parameter,
    /// Variants of the same group replace the same rule and cannot apply together (to
    /// the same record).
    pub group: &'static str,
    /// The rule of the spec it replaces.
    pub rule: &'static str,
    /// What it does instead.
    pub instead: &'static str,
    /// What of a pixel's path its rule is read on: for one record, that record; for the
    /// whole image, where a summary of the path can tell.
    pub reads: Reads,
    /// Where the rule it replaces is consulted at all.
    pub needs: Needs,
    /// For a mistake of one record: what it does to its record ("casts no shadow") and
    /// where in a student's program to look ("its hit test on shadow rays"); a `{}` in
    /// the first stands for the variant's value.
    pub advice: Option<(&'static str, &'static str)>,
}

/// What of a pixel's path the rule of a variant is read on: only the pixels whose paths
/// hold that (the variant's record, for one scoped to one) can change
/// (`compare --diagnose` re-traces those alone, src/compare/reach.rs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reads {
    /// The hits on its object (camera and mirror rays).
    Hits,
    /// Its object as a shadow ray's blocker.
    Blockers,
    /// Its light's terms.
    Lights,
    /// The mirror recursion past its first bounce: the paths that took a second.
    SecondBounce,
    /// How far the hits and the shadow rays' blockers lie: the paths that met something
    /// at the variant's value or beyond.
    Distances,
    /// Every record from its line on: the hits on those objects, them as blockers, and
    /// those lights' terms (the records before keep their places among the objects and
    /// the lights).
    Records,
    /// The geometry, or the image as a whole: any pixel may change.
    Anything,
}

/// Where the rule a variant replaces is consulted: without it in the scene and the
/// stage, the variant cannot change the image (`compare --diagnose` does not try it).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Needs {
    /// A light the stage lights.
    Light,
    /// An object that reflects (the one it is scoped to, or any) under a stage that
    /// reflects.
    Mirror,
    /// Either of those.
    LightOrMirror,
    /// Either of those, or the image of the normals.
    Shading,
    /// An object of the kinds it applies to, where it applies to every one of them.
    Kinds,
}

/// Declares [`Kind`] and [`VARIANTS`] from one list of rows, so that they cannot drift.
macro_rules! variants {
    ($($(#[$doc:meta])* $kind:ident: $id:literal, $site:ident, $scope:expr, $parameter:expr,
       $group:literal, $rule:literal, $instead:literal $(, reads $reads:ident)?
       $(, needs $needs:ident)? $(, advice $what:literal, $look:literal)?;)*) => {
        /// Which variant: one per row of [`VARIANTS`], in its order.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum Kind {
            $($(#[$doc])* $kind,)*
        }

        /// Every variant, in the order of spec §7.3 and §7.4.
        pub const VARIANTS: &[Row] = &[$(Row {
            kind: Kind::$kind,
            id: $id,
            site: Site::$site,
            scope: $scope,
            parameter: $parameter,
            group: $group,
            rule: $rule,
            instead: $instead,
            reads: or_default!(Reads, Anything $(, $reads)?),
            needs: or_default!(Needs, Kinds $(, $needs)?),
            advice: advice!($($what, $look)?),
        },)*];
    };
}

/// A row's column given, or its default.
macro_rules! or_default {
    ($type:ident, $default:ident) => {
        $type::$default
    };
    ($type:ident, $default:ident, $given:ident) => {
        $type::$given
    };
}

/// A row's advice, if given.
macro_rules! advice {
    () => {
        None
    };
    ($what:literal, $look:literal) => {
        Some(($what, $look))
    };
}

use Kinds::{Any, BoundedQuadrics, Cones, FramedPlanes, Planes, TiledPlanes};
use Scope::{Image, ImageOrLight, ImageOrObject, Light, Object, Record};

variants! {
    /// §4.1: the world point at (x + 0.5)/W instead of x/(W - 1).
    PixelCentre: "pixel-centre", Camera, Image, Parameter::None, "world point",
        "§4.1 world point x/(W-1)·ww - ww/2", "(x + 0.5)/W·ww - ww/2, and the same for y";
    /// §4.1: output row r holds y = r (bottom row first).
    UpsideDown: "upside-down", Camera, Image, Parameter::None, "rows",
        "§4.1 output row r holds y = H-1-r", "row r holds y = r: the image upside down";
    /// §4.7: bytes rounded half up instead of truncated.
    RoundBytes: "round-bytes", Bytes, Image, Parameter::None, "bytes",
        "§4.7 bytes truncated", "rounded half up: floor(255·c + 0.5)";
    /// §4.7: trunc(256 c) clamped to 255 instead of trunc(255 c).
    Scale256: "scale-256", Bytes, Image, Parameter::None, "bytes",
        "§4.7 ×255", "trunc(256·c), clamped to 255";
    /// §4.2 step 6: no division by the distance.
    NoDistance: "no-distance", Tracer, Image, Parameter::None, "divisor",
        "§4.2 step 6 I = I / total_dist", "no division";
    /// §4.2 step 6: divided by this segment's length, not the path's.
    SegmentDistance: "segment-distance", Tracer, Image, Parameter::None, "divisor",
        "§4.2 step 6 divides by the cumulative distance",
        "divides by the distance from this segment's base to the hit";
    /// §4.3: cos θ / dist² instead of cos θ / dist (every light, or one).
    SquareFalloff: "square-falloff", Tracer, ImageOrLight, Parameter::None, "falloff",
        "§4.3 cos θ / dist", "cos θ / dist²",
        reads Lights, needs Light;
    /// §4.3: no shadow rays (every light reaches), mirrors still reflect.
    NoShadows: "no-shadows", Tracer, Image, Parameter::None, "shadows",
        "§4.3 shadow ray", "every light reaches (stage diffuse, but with reflection)",
        needs Light;
    /// §4.2/§4.3: rays leaving a surface (every surface, or one) test every object and
    /// count hits with t > ε, instead of skipping the object they leave.
    ShadowEpsilon: "shadow-epsilon", Hits, ImageOrObject(Any),
        Parameter::Optional("E", DEFAULT_EPSILON), "leaving",
        "§4.2/§4.3 shadow and reflected rays skip the object they leave",
        "they test every object, counting hits with t > ε only (ε = 1e-6, or shadow-epsilon=E)",
        reads Hits, needs LightOrMirror;
    /// §4.4: the normal flipped toward the viewer (N·D > 0 → -N), on every object or one.
    FacingNormals: "facing-normals", Tracer, ImageOrObject(Any), Parameter::None, "normal",
        "§4.4 normals never flipped", "N flipped when N·D > 0",
        reads Hits, needs Shading;
    /// §5.1: no miss for plane hits with z > 0, on every plane or one.
    NoZRule: "no-z-rule", Scene, ImageOrObject(Planes), Parameter::None, "z rule",
        "§5.1 miss if z > 0", "no z test";
    /// §5.4: even relx + rely → foreground, on every tiled plane or one.
    TileParity: "tile-parity", Scene, ImageOrObject(TiledPlanes), Parameter::None, "parity",
        "§5.4 odd relx + rely → foreground", "even → foreground",
        reads Hits;
    /// §5.6: the cone's k = r²/h (the paraboloid's) instead of (r/h)², on every cone or
    /// one.
    ConeScale: "cone-scale", Scene, ImageOrObject(Cones), Parameter::None, "cone k",
        "§3.2/§5.6 cone k = (r/h)²", "k = r²/h (the paraboloid's formula)";
    /// §5.6: the quadrics 21-24 (every one, or one) try only the smaller root; out of
    /// bounds is a miss.
    NearerRoot: "nearer-root", Scene, ImageOrObject(BoundedQuadrics), Parameter::None, "root",
        "§5.6 smallest positive root in bounds",
        "only the smaller root is tried; out of bounds is a miss",
        advice "tries only its smaller root",
            "the root its test returns: the other one when the first is out of bounds";
    /// §4.5: at most one reflected ray per camera ray.
    OneBounce: "one-bounce", Tracer, Image, Parameter::None, "bounces",
        "§4.5 recursion", "at most one reflected ray per camera ray",
        reads SecondBounce, needs Mirror;
    /// §4.2: MAX_DIST D instead of 32.
    MaxDist: "max-dist", Option, Image, Parameter::Required("D", 70.0), "max-dist",
        "§4.2 MAX_DIST 32", "MAX_DIST D (one term of the course used 70)";
    /// §4.1 (§7.5): every row shows the pixel traced N rows up, as `rows - y` for
    /// `rows - 1 - y` does (N = 1).
    RowOffset: "row-offset", Camera, Image, Parameter::Integer("N", 1.0), "row offset",
        "§4.1 output row r holds y = H-1-r",
        "row r holds the pixel traced at y = H-1-r+N (N = 1: rows - y for rows - 1 - y; the top row traces a point just beyond the window)";
    /// §4.1 (§7.5): every column shows the pixel traced N columns right.
    ColumnOffset: "column-offset", Camera, Image, Parameter::Integer("N", 1.0), "column offset",
        "§4.1 column x holds pixel x",
        "column x holds the pixel traced at x+N (beyond the window where x+N leaves it)";
    /// §4.1 (§7.5): each camera ray through a point drawn within half a pixel of P.
    Jitter: "jitter", Camera, Image, Parameter::Optional("SEED", 1.0), "jitter",
        "§4.1 one ray through P, no jitter",
        "the ray through a point drawn uniformly within half a pixel of P in x and y (a fixed seed, default 1: the image is reproducible)";
    /// §5.6 (§7.5): the smaller root in bounds even when <= 0, which §4.6 rejects: a ray
    /// from inside a tube misses it.
    BehindRoot: "behind-root", Scene, ImageOrObject(BoundedQuadrics), Parameter::None, "root",
        "§5.6 the smallest positive root in bounds",
        "the smaller root in bounds even when it is <= 0, which §4.6 then rejects (the sphere's rule of §5.2): a ray whose base is inside the surface misses it",
        advice "keeps its smaller root in bounds even behind the ray's base (a ray from inside it misses it)",
            "the root its test returns: the smallest in bounds that is > 0 (spec §5.6)";
    /// §5.1 (§7.5): a plane's hit counts up to z = E, not 0.
    ZTolerance: "z-tolerance", Scene, ImageOrObject(Planes), Parameter::Required("E", 0.01), "z rule",
        "§5.1 miss if z > 0", "miss if z > E",
        advice "counts hits up to z = {}", "its z > 0 test (spec §5.1)";
    /// §4.6 (§7.5): a hit farther than D from the ray's base is a miss.
    FarClip: "far-clip", Hits, Image, Parameter::Required("D", 32.0), "far clip",
        "§4.6 any t > 0 counts",
        "a hit farther than D from the ray's base is a miss (a closest-hit search that starts from mindist = D)",
        reads Distances;
    /// §5.3/§5.4 (§7.5): the frame's x is unit(xdir) as given, not projected into the
    /// plane, on every framed plane or one.
    TileUnprojected: "tile-unprojected", Scene, ImageOrObject(FramedPlanes), Parameter::None, "frame",
        "§5.3/§5.4 x projected into the plane",
        "x = unit(xdir) used as given: where it leaves the plane, (q.x, q.y) shrink by the length of x - (n·x)n, so the rectangle and the tiles grow";
    /// §2.3 (§7.5): the records from LINE on are not loaded.
    StoppedAt: "stopped-at", Scene, Record, Parameter::None, "stopped",
        "§2.3 records to the end of the file",
        "the records from LINE on are not loaded (a reader that stopped there without an error)",
        reads Records, advice "and every record after it are not loaded",
            "the loop that reads the records: it must go on to the end of the file (spec §2.3)";
    /// The notes' root formula in f64 (`--kernel textbook`).
    Textbook: "textbook", Option, Image, Parameter::None, "kernel",
        "the accurate roots", "the notes' (-b ± sqrt(b² - 4ac)) / 2a in f64";
    /// The notes' root formula in f32 (`--kernel textbook-f32`).
    TextbookF32: "textbook-f32", Option, Image, Parameter::None, "kernel",
        "the accurate roots", "the notes' (-b ± sqrt(b² - 4ac)) / 2a in f32";
    /// §7.4: camera and mirror rays pass through the object.
    Hidden: "hidden", Hits, Object(Any), Parameter::None, "hidden",
        "§4.6 every object is a candidate for camera and mirror rays",
        "camera and mirror rays pass through the object",
        reads Hits,
        advice "is not seen", "its hit test on camera and mirror rays";
    /// §7.4: the object casts no shadow.
    NoShadow: "no-shadow", Hits, Object(Any), Parameter::None, "casts",
        "§4.3 every object may block a shadow ray",
        "the object casts no shadow (shadow rays pass through it)",
        reads Blockers, needs Light,
        advice "casts no shadow", "its hit test on shadow rays";
    /// §7.4: no light adds to the object.
    Unlit: "unlit", Tracer, Object(Any), Parameter::None, "lit",
        "§4.3 every light adds to the object",
        "the object receives no diffuse light (ambient and mirror only)",
        reads Hits, needs Light,
        advice "receives no diffuse light", "its diffuse term";
    /// §7.4: the object's specular reflection is not traced.
    NoMirror: "no-mirror", Tracer, Object(Any), Parameter::None, "mirror",
        "§4.5 reflection where the specular is non-zero",
        "the object's specular reflection is not traced",
        reads Hits, needs Mirror,
        advice "reflects nothing", "its mirror ray";
    /// §7.4: the object's normal is reversed at every hit.
    FlippedNormal: "flipped-normal", Tracer, Object(Any), Parameter::None, "normal",
        "§4.4 the normal as computed", "the object's normal is reversed at every hit",
        reads Hits, needs Shading,
        advice "has its normal reversed", "its normal";
    /// §7.4: the light is off.
    NoLight: "no-light", Tracer, Light, Parameter::None, "light",
        "§4.2 step 5 every light", "the light is off",
        reads Lights, needs Light,
        advice "is off", "the loop over the lights";
    /// §7.4: the light's shadow rays are never blocked.
    Unshadowed: "unshadowed", Tracer, Light, Parameter::None, "shadows",
        "§4.3 the shadow test", "the light's shadow rays are never blocked",
        reads Lights, needs Light,
        advice "is never blocked", "its shadow rays";
}

impl Kind {
    /// Its row of [`VARIANTS`].
    pub fn row(self) -> &'static Row {
        &VARIANTS[self as usize]
    }
}

/// A variant as given: which, its value (`max-dist=70`, `shadow-epsilon=1e-3`) and the
/// line of the record it is scoped to (`@34`), if any.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Variant {
    /// The row of [`VARIANTS`] that says what it replaces.
    pub kind: Kind,
    /// The parameter's value, where the row has one.
    pub value: Option<f64>,
    /// The line of the one record it applies to; `None` for the whole image.
    pub line: Option<usize>,
}

impl Variant {
    /// The variant `kind` for the whole image, with its parameter's default (max-dist
    /// takes the other term's 70).
    pub fn of(kind: Kind) -> Variant {
        let value = match kind.row().parameter {
            Parameter::None => None,
            Parameter::Optional(_, default)
            | Parameter::Required(_, default)
            | Parameter::Integer(_, default) => Some(default),
        };
        Variant {
            kind,
            value,
            line: None,
        }
    }

    /// The same variant for the one record on `line`.
    pub fn at(self, line: usize) -> Variant {
        Variant {
            line: Some(line),
            ..self
        }
    }

    /// Every variant of the table that applies to a whole image, with its default value,
    /// in the table's order (the edits that exist only scoped are left out).
    pub fn all() -> impl Iterator<Item = Variant> {
        VARIANTS
            .iter()
            .filter(|row| !matches!(row.scope, Scope::Object(_) | Scope::Light | Scope::Record))
            .map(|row| Variant::of(row.kind))
    }

    /// Every variant `compare --diagnose` tries on its own, in the table's order: those of
    /// [`Variant::all`] but max-dist=D, whose D is estimated instead.
    pub fn tried() -> impl Iterator<Item = Variant> {
        Variant::all().filter(|v| v.kind != Kind::MaxDist)
    }

    /// Its row of [`VARIANTS`]: id, rule, what it does instead.
    pub fn row(self) -> &'static Row {
        self.kind.row()
    }

    /// The id as `--variant` takes it back: `max-dist=70`, `shadow-epsilon=0.001@12`,
    /// `no-shadow@12` (plain `shadow-epsilon` for the default ε).
    pub fn id(self) -> String {
        let row = self.row();
        let mut id = row.id.to_string();
        match (row.parameter, self.value) {
            (Parameter::Required(..) | Parameter::Integer(..), Some(v)) => id += &format!("={v}"),
            (Parameter::Optional(_, default), Some(v)) if v != default => id += &format!("={v}"),
            _ => {}
        }
        if let Some(line) = self.line {
            id += &format!("@{line}");
        }
        id
    }

    /// The id as the table and `--help` write it: `max-dist=D`, `shadow-epsilon[=E]`,
    /// `no-shadow@LINE`, `facing-normals[@LINE]`.
    pub fn pattern(row: &Row) -> String {
        let mut id = row.id.to_string();
        match row.parameter {
            Parameter::None => {}
            Parameter::Required(name, _) | Parameter::Integer(name, _) => id += &format!("={name}"),
            Parameter::Optional(name, _) => id += &format!("[={name}]"),
        }
        match row.scope {
            Scope::Image => {}
            Scope::ImageOrObject(_) | Scope::ImageOrLight => id += "[@LINE]",
            Scope::Object(_) | Scope::Light | Scope::Record => id += "@LINE",
        }
        id
    }

    /// The variant named `text`: an id, with `=VALUE` where it takes one and `@LINE`
    /// where it may be scoped.
    pub fn parse(text: &str) -> Result<Variant, String> {
        let (name, line) = match text.rsplit_once('@') {
            Some((name, line)) => match line.parse::<usize>() {
                Ok(line) if line > 0 => (name, Some(line)),
                _ => return Err(format!("{text}: @ takes the line of a record, such as @12")),
            },
            None => (text, None),
        };
        let (id, value) = match name.split_once('=') {
            Some((id, value)) => (id, Some(value)),
            None => (name, None),
        };
        let Some(row) = VARIANTS.iter().find(|row| row.id == id) else {
            let ids: Vec<String> = VARIANTS.iter().map(Variant::pattern).collect();
            return Err(format!(
                "unknown variant {text:?}; the variants are: {}",
                ids.join(", ")
            ));
        };
        let number = |value: &str| match value.parse::<f64>() {
            Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
            _ => Err(format!(
                "{id}= takes a number greater than 0, found {value:?}"
            )),
        };
        let whole = |value: &str| match value.parse::<i64>() {
            Ok(n) if n != 0 && n.abs() <= 1_000_000 => Ok(n as f64),
            _ => Err(format!(
                "{id}= takes a whole number other than 0 (of either sign), found {value:?}"
            )),
        };
        let value = match (row.parameter, value) {
            (Parameter::None, None) => None,
            (Parameter::None, Some(_)) => return Err(format!("{id} takes no value")),
            (Parameter::Required(name, example) | Parameter::Integer(name, example), None) => {
                return Err(format!(
                    "{id} takes its value: {id}={name}, such as {}",
                    Variant {
                        kind: row.kind,
                        value: Some(example),
                        line: None
                    }
                    .id()
                ));
            }
            (Parameter::Optional(_, default), None) => Some(default),
            (Parameter::Integer(..), Some(value)) => Some(whole(value)?),
            (_, Some(value)) => Some(number(value)?),
        };
        match (row.scope, line) {
            (Scope::Image, Some(_)) => {
                return Err(format!(
                    "{id} applies to the whole image; it takes no @LINE"
                ));
            }
            (Scope::Object(_), None) => {
                return Err(format!(
                    "{id} applies to one object: {id}@LINE, with the line of its type code"
                ));
            }
            (Scope::Light, None) => {
                return Err(format!(
                    "{id} applies to one light: {id}@LINE, with the line of its type code"
                ));
            }
            (Scope::Record, None) => {
                return Err(format!(
                    "{id} names a record: {id}@LINE, with the line of its type code"
                ));
            }
            _ => {}
        }
        Ok(Variant {
            kind: row.kind,
            value,
            line,
        })
    }

    /// "what it does instead of the rule it replaces", with the variant's value and scope.
    pub fn describe(self) -> String {
        let row = self.row();
        let instead = match (self.kind, self.value) {
            (Kind::MaxDist, Some(d)) => format!("MAX_DIST {d}"),
            (Kind::RowOffset, Some(n)) => {
                format!(
                    "every row shows the pixel traced {} row(s) {}",
                    n.abs(),
                    if n > 0.0 { "up" } else { "down" }
                )
            }
            (Kind::ColumnOffset, Some(n)) => {
                format!(
                    "every column shows the pixel traced {} column(s) {}",
                    n.abs(),
                    if n > 0.0 { "right" } else { "left" }
                )
            }
            (Kind::ZTolerance, Some(e)) => format!("a plane's hit counts up to z = {e}"),
            (Kind::FarClip, Some(d)) => {
                format!("a hit farther than {d} from the ray's base is a miss")
            }
            (Kind::StoppedAt, _) => {
                let line = self.line.map_or(String::new(), |l| format!(" on line {l}"));
                return format!(
                    "the record{line} and every one after it are not loaded, instead of {}",
                    row.rule
                );
            }
            (Kind::ShadowEpsilon, Some(e)) if self.line.is_none() => {
                format!("rays leaving a surface test every object, counting hits with t > {e} only")
            }
            (Kind::ShadowEpsilon, Some(e)) => {
                format!("rays leaving it test every object, counting hits with t > {e} only")
            }
            _ => row.instead.to_string(),
        };
        let scope = match self.line {
            Some(line) => format!(" for the record on line {line}"),
            None => String::new(),
        };
        format!("{instead}{scope}, instead of {}", row.rule)
    }
}

/// The table of [`VARIANTS`] as docs/variants.md shows it: a Markdown row per variant,
/// with its id, the rule it replaces, what it does instead, and what it may apply to.
pub fn markdown_table() -> String {
    let mut table = String::from(
        "| id | the rule of the spec it replaces | what it does instead | applies to |\n\
         |---|---|---|---|\n",
    );
    for row in VARIANTS {
        let applies = match row.scope {
            Scope::Image => "the image".to_string(),
            Scope::ImageOrObject(kinds) => format!("the image, or one of its {}", kinds.name()),
            Scope::Object(kinds) => format!("one of the {}", kinds.name()),
            Scope::ImageOrLight => "the image, or one light".to_string(),
            Scope::Light => "one light".to_string(),
            Scope::Record => "the record on LINE and those after it".to_string(),
        };
        table += &format!(
            "| `{}` | {} | {} | {applies} |\n",
            Variant::pattern(row),
            row.rule,
            row.instead
        );
    }
    table
}

/// A variant is written as its id (`no-shadow@12`), as `--variant` takes it back.
impl serde::Serialize for Variant {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(&self.id())
    }
}

/// Up to [`Variants::MOST`] variants, in the order given: a list that keeps [`Options`]
/// `Copy`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Variants {
    list: [Option<Variant>; Variants::MOST],
}

impl Variants {
    /// The most variants one render applies.
    pub const MOST: usize = 16;

    /// The variants, in order.
    pub fn iter(&self) -> impl Iterator<Item = Variant> + '_ {
        self.list.iter().map_while(|v| *v)
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.list[0].is_none()
    }

    fn push(&mut self, variant: Variant) -> Result<(), ChoiceError> {
        match self.list.iter_mut().find(|v| v.is_none()) {
            Some(slot) => {
                *slot = Some(variant);
                Ok(())
            }
            None => Err(ChoiceError::TooMany(Variants::MOST)),
        }
    }
}

impl Options {
    /// These options with each of `variants` applied in turn ([`Options::with_variant`]).
    pub fn with_variants(&self, variants: &[Variant]) -> Result<Options, ChoiceError> {
        (variants.iter()).try_fold(*self, |options, &variant| options.with_variant(variant))
    }

    /// These options with `variant` applied; an error when a variant already applied
    /// replaces the same rule for the same records (two byte rules, two divisors, two
    /// kernels, two MAX_DISTs, shadow-epsilon twice for one object).
    pub fn with_variant(&self, variant: Variant) -> Result<Options, ChoiceError> {
        let mut options = *self;
        let conflict = |first: String| ChoiceError::Conflict {
            first,
            second: variant.id(),
        };
        match variant.row().site {
            Site::Option => {
                if let Some(first) = option_taken(self, variant.kind) {
                    return Err(conflict(first));
                }
                set_option(&mut options, variant);
            }
            _ => {
                let group = variant.row().group;
                let same_records = |other: Variant| {
                    other.line.is_none() || variant.line.is_none() || other.line == variant.line
                };
                if let Some(first) = (self.variants.iter())
                    .find(|&v| v.row().group == group && v.kind != variant.kind && same_records(v))
                    .or_else(|| {
                        // The same variant twice for one record, with two values.
                        (self.variants.iter())
                            .find(|&v| v.kind == variant.kind && v.line == variant.line)
                            .filter(|v| v.value != variant.value)
                    })
                {
                    return Err(conflict(first.id()));
                }
                options.variants.push(variant)?;
            }
        }
        Ok(options)
    }

    /// The variants these options apply, the options' own (MAX_DIST, the kernel) included,
    /// in the table's order.
    pub fn all_variants(&self) -> Vec<Variant> {
        let mut all: Vec<Variant> = self.variants.iter().collect();
        all.extend(option_variants(self));
        all.sort_by_key(|v| (v.kind, v.line));
        all
    }

    /// The output row that holds pixel row `y` (0 at the bottom): H - 1 - y (spec §4.1),
    /// or y under upside-down. The map is its own inverse: it also gives the pixel row
    /// that output row `y` holds.
    pub fn row_of(&self, y: usize) -> usize {
        let upside_down = self.variants.iter().any(|v| v.kind == Kind::UpsideDown);
        output_row(y, self.height, upside_down)
    }
}

/// The variants whose rule is a render option ([`Site::Option`]: MAX_DIST and the
/// kernel), written into their fields of [`Options`] here and read back from them by
/// [`option_variants`]: the one place that knows which field each sets.
fn set_option(options: &mut Options, variant: Variant) {
    match variant.kind {
        Kind::MaxDist => options.max_dist = variant.value.unwrap_or(DEFAULT_MAX_DIST),
        Kind::Textbook => options.kernel = KernelChoice::Textbook,
        Kind::TextbookF32 => options.kernel = KernelChoice::TextbookF32,
        kind => unreachable!("{} is not a render option", kind.row().id),
    }
}

/// What the field that option variant `kind` sets already holds in `options`, where it is
/// not the default render's: the variant that set it (`max-dist=70`), or the kernel's
/// name where no variant names it (`stable`).
fn option_taken(options: &Options, kind: Kind) -> Option<String> {
    let group = kind.row().group;
    let held = option_variants(options).find(|v| v.row().group == group);
    let kernel = options.kernel != KernelChoice::Accurate && group == Kind::Textbook.row().group;
    held.map(Variant::id)
        .or_else(|| kernel.then(|| options.kernel.name().into()))
}

/// The option variants that `options` hold: each field that differs from the default
/// render's, as the variant that sets it (the inverse of [`set_option`]).
fn option_variants(options: &Options) -> impl Iterator<Item = Variant> {
    let max_dist = (options.max_dist != DEFAULT_MAX_DIST).then(|| Variant {
        value: Some(options.max_dist),
        ..Variant::of(Kind::MaxDist)
    });
    let kernel = match options.kernel {
        KernelChoice::Accurate | KernelChoice::Stable => None,
        KernelChoice::Textbook => Some(Variant::of(Kind::Textbook)),
        KernelChoice::TextbookF32 => Some(Variant::of(Kind::TextbookF32)),
    };
    max_dist.into_iter().chain(kernel)
}

/// The output row of an image `height` rows high that holds pixel row `y` (0 at the
/// bottom), and the reverse: H - 1 - y (spec §4.1), or y where the image is written
/// upside down (spec §7.3).
pub(crate) fn output_row(y: usize, height: usize, upside_down: bool) -> usize {
    if upside_down { y } else { height - 1 - y }
}

/// Checks that every scoped variant of `options` names the line of a record of the kind it
/// applies to in `scene`; the error names the lines that would do.
pub fn check_scopes(options: &Options, scene: &Scene) -> Result<(), ChoiceError> {
    for variant in options.variants.iter() {
        let Some(line) = variant.line else { continue };
        let row = variant.row();
        let objects = |kinds: Kinds| -> Vec<usize> {
            (scene.objects.iter())
                .filter(|o| kinds.admit(&o.shape))
                .map(|o| o.line)
                .collect()
        };
        let (fits, kinds) = match row.scope {
            Scope::ImageOrObject(kinds) | Scope::Object(kinds) => (objects(kinds), kinds.name()),
            Scope::ImageOrLight | Scope::Light => {
                let lines = scene.lights.iter().map(|l| l.line).collect();
                (lines, "lights")
            }
            Scope::Record => {
                let mut lines: Vec<usize> = (scene.objects.iter().map(|o| o.line))
                    .chain(scene.lights.iter().map(|l| l.line))
                    .collect();
                lines.sort_unstable();
                (lines, "records")
            }
            Scope::Image => continue,
        };
        if fits.contains(&line) {
            continue;
        }
        let there = (scene.objects.iter().map(|o| (o.line, o.kind())))
            .chain(scene.lights.iter().map(|l| (l.line, "light")))
            .find(|&(at, _)| at == line)
            .map(|(_, kind)| format!("line {line} starts a {kind}"))
            .unwrap_or_else(|| format!("line {line} starts no record"));
        let lines = match fits.is_empty() {
            true => format!("the scene has no {kinds}"),
            false => {
                let list: Vec<String> = fits.iter().map(|l| l.to_string()).collect();
                format!("the {kinds} start on lines {}", list.join(", "))
            }
        };
        return Err(ChoiceError::Scope {
            id: variant.id(),
            there,
            applies: row.id,
            kinds,
            lines,
        });
    }
    Ok(())
}

/// 2^52 + 2^51: a number x with |x| < 2^51, plus this, minus this, is the integer nearest
/// to x (IEEE arithmetic rounds to nearest).
const ROUNDER: f64 = 6_755_399_441_055_744.0;

/// How a channel becomes a byte (spec §4.7 or a variant of it).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum Bytes {
    /// Clamp, ×255, truncate (spec §4.7).
    #[default]
    Truncate,
    /// round-bytes: floor(255 c + 0.5).
    Round,
    /// scale-256: trunc(256 c), clamped to 255.
    Scale256,
}

impl Bytes {
    /// A colour's three bytes under this rule.
    #[inline(always)]
    pub(crate) fn of(self, colour: DVec3) -> [u8; 3] {
        // The rule chosen once, not per channel.
        let channels = colour.to_array();
        match self {
            Bytes::Truncate => channels.map(|c| Bytes::Truncate.byte(c)),
            Bytes::Round => channels.map(|c| Bytes::Round.byte(c)),
            Bytes::Scale256 => channels.map(|c| Bytes::Scale256.byte(c)),
        }
    }

    /// The byte of `channel` under this rule. NaN gives 0.
    #[inline]
    pub(crate) fn byte(self, channel: f64) -> u8 {
        // The cast truncates (the floor of these values from 0 up) and saturates: below
        // 0 and NaN give 0, above 255 gives 255, which clamps the channel to [0, 1]
        // first would give too.
        match self {
            Bytes::Truncate => to_byte(channel),
            Bytes::Round => (channel * 255.0 + 0.5) as u8,
            Bytes::Scale256 => (channel * 256.0) as u8,
        }
    }

    /// How far `channel` lies from the nearest value where its byte changes, relative to
    /// the channel: |v - k| / v with v the scaled channel (255 c, or 256 c) and k the
    /// nearest step (an integer for truncation, an integer plus ½ for round-bytes). A
    /// channel of exactly 0 (nothing lit it, nothing reflected into it) or NaN is 0 in
    /// any arithmetic: infinite. Above the clamp the step is the clamp's own.
    #[cfg(test)]
    fn margin(self, channel: f64) -> f64 {
        self.step_distance(channel)
            .map_or(f64::INFINITY, |(distance, scaled)| distance / scaled)
    }

    /// Whether `channel`'s margin (|v - k| / v, as above) is below `limit`: compared as
    /// |v - k| < limit · v, without a division (three a pixel, in the reference's every
    /// pixel).
    #[inline]
    pub(crate) fn fragile(self, channel: f64, limit: f64) -> bool {
        self.step_distance(channel)
            .is_some_and(|(distance, scaled)| distance < limit * scaled)
    }

    /// |v - k| and v of the margin above; `None` for a channel of 0 or NaN.
    #[inline]
    fn step_distance(self, channel: f64) -> Option<(f64, f64)> {
        if channel.is_nan() || channel <= 0.0 {
            return None;
        }
        let (scaled, offset, top) = match self {
            Bytes::Truncate => (channel * 255.0, 0.0, 255.0),
            Bytes::Round => (channel * 255.0, 0.5, 254.5),
            Bytes::Scale256 => (channel * 256.0, 0.0, 255.0),
        };
        if scaled >= top {
            // 255 from the last step up.
            return Some((scaled - top, scaled));
        }
        let x = scaled - offset;
        if x < 0.0 {
            // 0 up to the first step.
            return Some((-x, scaled));
        }
        // The distance to the nearer of the steps on either side: to the nearest integer
        // k, found by adding and taking away 2^52 + 2^51 (exact below 2^51; no cast, no
        // rounding call), |x - k| exact.
        let nearest = (x + ROUNDER) - ROUNDER;
        Some(((x - nearest).abs(), scaled))
    }
}

/// What step 6 of spec §4.2 divides by.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum Divisor {
    /// The path's cumulative length (spec §4.2).
    #[default]
    Path,
    /// no-distance: no division.
    Nothing,
    /// segment-distance.
    Segment,
}

/// The variants one object, or one light, follows: a bit for each kind of [`VARIANTS`],
/// read where its rule lives (`has(Kind::Hidden)`), all in one load. [`Rules::new`] sets
/// the bit of every row whose rule one object or one light follows, so a new variant of
/// one record needs its row and the line that reads its bit, nothing here.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct Applied(u64);

// A bit for each kind.
const _: () = assert!(VARIANTS.len() <= 64);

impl Applied {
    /// Whether variant `kind` applies.
    #[inline(always)]
    pub(crate) fn has(self, kind: Kind) -> bool {
        self.0 >> kind as u32 & 1 != 0
    }

    /// These, and `kind`.
    fn with(self, kind: Kind) -> Applied {
        Applied(self.0 | 1 << kind as u32)
    }
}

/// The variants one object follows.
pub(crate) type ObjectRules = Applied;

/// The variants one light follows.
pub(crate) type LightRules = Applied;

/// The rules of spec §4-§5 as a render applies them: as written, but where a variant
/// replaces one. The tracer, the aggregate and the camera read these values where each
/// rule lives.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct Rules {
    /// pixel-centre: pixels sampled at their centres.
    pub(crate) pixel_centre: bool,
    /// upside-down: output row r holds pixel row r.
    pub(crate) upside_down: bool,
    /// §4.7's conversion.
    pub(crate) bytes: Bytes,
    /// §4.2 step 6's divisor.
    pub(crate) divisor: Divisor,
    /// one-bounce: at most this many reflected rays.
    pub(crate) bounces: usize,
    /// Per object, in the scene's order.
    pub(crate) objects: Box<[ObjectRules]>,
    /// The variants some object follows: the aggregate looks at each object's rules only
    /// for those.
    pub(crate) some: Applied,
    /// Per object, shadow-epsilon's ε for the rays leaving it, where it applies.
    pub(crate) epsilons: Option<Box<[Option<f64>]>>,
    /// Per light, in the scene's order.
    pub(crate) lights: Box<[LightRules]>,
    /// row-offset and column-offset: the pixel each row and column traces, so many away.
    pub(crate) row_offset: i64,
    /// See `row_offset`.
    pub(crate) column_offset: i64,
    /// jitter: the seed of each pixel's point within half a pixel of its own.
    pub(crate) jitter: Option<u64>,
    /// far-clip: hits at this distance or farther are misses (∞ as written).
    pub(crate) far: f64,
}

impl Rules {
    /// The rules of `options`' variants on `scene` (objects and lights by index). A scoped
    /// variant whose line starts no record of its kind applies to nothing
    /// ([`check_scopes`] tells the user first).
    pub(crate) fn new(options: &Options, scene: &Scene) -> Rules {
        let mut rules = Rules {
            bounces: super::MAX_BOUNCES,
            far: f64::INFINITY,
            ..Rules::default()
        };
        let mut objects = vec![ObjectRules::default(); scene.objects.len()];
        let mut epsilons = vec![None; scene.objects.len()];
        let mut lights = vec![LightRules::default(); scene.lights.len()];
        for variant in options.variants.iter() {
            let scoped = |line: usize| variant.line.is_none_or(|at| at == line);
            let object_indices: Vec<usize> = (scene.objects.iter().enumerate())
                .filter(|(_, o)| scoped(o.line))
                .map(|(i, _)| i)
                .collect();
            let light_indices: Vec<usize> = (scene.lights.iter().enumerate())
                .filter(|(_, l)| scoped(l.line))
                .map(|(i, _)| i)
                .collect();
            let mut set_objects = |kind: Kind| {
                object_indices
                    .iter()
                    .for_each(|&i| objects[i] = objects[i].with(kind));
            };
            let mut set_lights = |kind: Kind| {
                light_indices
                    .iter()
                    .for_each(|&i| lights[i] = lights[i].with(kind));
            };
            match variant.kind {
                Kind::PixelCentre => rules.pixel_centre = true,
                Kind::UpsideDown => rules.upside_down = true,
                Kind::RoundBytes => rules.bytes = Bytes::Round,
                Kind::Scale256 => rules.bytes = Bytes::Scale256,
                Kind::NoDistance => rules.divisor = Divisor::Nothing,
                Kind::SegmentDistance => rules.divisor = Divisor::Segment,
                Kind::OneBounce => rules.bounces = 1,
                Kind::ShadowEpsilon => {
                    let epsilon = variant.value.unwrap_or(DEFAULT_EPSILON);
                    object_indices
                        .iter()
                        .for_each(|&i| epsilons[i] = Some(epsilon));
                }
                // Every light's shadow rays unblocked: unshadowed on each.
                Kind::NoShadows => set_lights(Kind::Unshadowed),
                Kind::RowOffset => rules.row_offset = variant.value.unwrap_or(1.0) as i64,
                Kind::ColumnOffset => rules.column_offset = variant.value.unwrap_or(1.0) as i64,
                Kind::Jitter => rules.jitter = Some(variant.value.unwrap_or(1.0) as u64),
                Kind::FarClip => rules.far = variant.value.unwrap_or(f64::INFINITY),
                // A rule one object, or one light, follows where the tracer or the hits
                // read it: its bit. The others are the scene's (`Rules::scene`) and the
                // options' own.
                kind => match (variant.row().site, variant.row().scope) {
                    (Site::Hits | Site::Tracer, Scope::Object(_) | Scope::ImageOrObject(_)) => {
                        set_objects(kind)
                    }
                    (Site::Tracer, Scope::Light | Scope::ImageOrLight) => set_lights(kind),
                    _ => {}
                },
            }
        }
        rules.some = Applied(objects.iter().fold(0, |some, o| some | o.0));
        rules.objects = objects.into();
        rules.epsilons = epsilons
            .iter()
            .any(Option::is_some)
            .then(|| epsilons.into());
        rules.lights = lights.into();
        rules
    }

    /// Whether the tracer's rules are all as written (spec §4-§5): no variant of the
    /// tracer, the hits or the bytes applies, whatever those of the camera or the scene
    /// do. A render then reads them from [`AsWritten`].
    pub(crate) fn as_written(&self) -> bool {
        self.bytes == Bytes::Truncate
            && self.objects.iter().all(|o| *o == ObjectRules::default())
            && self.lights.iter().all(|l| *l == LightRules::default())
            && self.epsilons.is_none()
            && self.bounces == super::MAX_BOUNCES
            && self.divisor == Divisor::Path
            && self.far == f64::INFINITY
    }

    /// A colour's bytes (spec §4.7, or round-bytes or scale-256).
    #[inline(always)]
    pub(crate) fn bytes(&self, colour: DVec3) -> [u8; 3] {
        self.bytes.of(colour)
    }

    /// The scene as the variants of its geometry change it (no-z-rule, tile-parity,
    /// cone-scale, nearer-root, on every record they apply to or on one): borrowed
    /// unchanged when none applies.
    pub(crate) fn scene<'a>(options: &Options, scene: &'a Scene) -> Cow<'a, Scene> {
        let in_scene = |v: &Variant| v.row().site == Site::Scene;
        if !options.variants.iter().any(|v| in_scene(&v)) {
            return Cow::Borrowed(scene);
        }
        let mut scene = scene.clone();
        for variant in options.variants.iter().filter(in_scene) {
            if let (Kind::StoppedAt, Some(line)) = (variant.kind, variant.line) {
                // The reader stopped at `line`: that record and every later one are gone.
                scene.objects.retain(|o| o.line < line);
                scene.lights.retain(|l| l.line < line);
                continue;
            }
            let objects = (scene.objects.iter_mut())
                .filter(|object| variant.line.is_none_or(|line| object.line == line));
            for object in objects {
                match variant.kind {
                    // Only a tiled plane's look is copied (`make_mut`: the unvaried scene
                    // shares it); every other object keeps sharing its own.
                    Kind::TileParity if matches!(object.look.pattern, Pattern::Tiles { .. }) => {
                        let look = Arc::make_mut(&mut object.look);
                        if let Pattern::Tiles { background, .. } = &mut look.pattern {
                            // Even relx + rely now picks the first material: the same as
                            // swapping the two materials under the odd rule.
                            std::mem::swap(&mut look.material, &mut **background);
                        }
                    }
                    Kind::ConeScale => {
                        if let Shape::Cone(cone) = &mut object.shape {
                            let size = cone.size;
                            let frame = cone.equation.frame.clone();
                            **cone = Cone::with_k(frame, size, size.radius.powi(2) / size.height);
                        }
                    }
                    Kind::NoZRule => {
                        if let Some(plane) = object.shape.plane_mut() {
                            plane.z_limit = f64::INFINITY;
                        }
                    }
                    Kind::ZTolerance => {
                        if let Some(plane) = object.shape.plane_mut() {
                            plane.z_limit = variant.value.unwrap_or(0.0);
                        }
                    }
                    Kind::NearerRoot => {
                        if let Some(quadric) = object.shape.bounded_axis_quadric_mut() {
                            quadric.smaller_root_only();
                        }
                    }
                    Kind::BehindRoot => {
                        if let Some(quadric) = object.shape.bounded_axis_quadric_mut() {
                            quadric.smaller_root_even_behind();
                        }
                    }
                    Kind::TileUnprojected => {
                        if let Some(frame) = object.shape.frame_mut() {
                            frame.unproject();
                        }
                    }
                    _ => {}
                }
            }
        }
        Cow::Owned(scene)
    }
}

/// Where the tracer and the aggregate read the rules of spec §4-§5 that variants replace:
/// each method is the rule's value at its site. A render with variants reads its [`Rules`];
/// the plain render reads [`AsWritten`], whose answers are constants, so that the rules
/// as written cost it nothing (measured in docs/architecture.md: the plain render with
/// `&Rules` took 11 % more instructions on the course scene spec1).
pub(crate) trait Rulebook: Copy + Send + Sync {
    /// Object `index`'s rules.
    fn object(self, index: usize) -> ObjectRules;
    /// Light `index`'s rules.
    fn light(self, index: usize) -> LightRules;
    /// shadow-epsilon's ε for rays leaving object `index`, if it applies.
    fn epsilon(self, index: usize) -> Option<f64>;
    /// Whether some object follows variant `kind` (hidden: camera and mirror rays then
    /// ask each object; no-shadow: shadow rays do).
    fn some(self, kind: Kind) -> bool;
    /// The most reflected rays per camera ray (spec §4.5, or one-bounce).
    fn bounces(self) -> usize;
    /// What step 6 of spec §4.2 divides by.
    fn divisor(self) -> Divisor;
    /// Hits at this distance or farther are misses: under far-clip only (`None` as
    /// written, which the compiler leaves out of the hit tests of [`AsWritten`]).
    fn far(self) -> Option<f64>;
    /// How a colour becomes bytes (spec §4.7, or round-bytes or scale-256).
    fn bytes(self) -> Bytes;
}

/// The rules of spec §4-§5 as written, known when the tracer is compiled.
#[derive(Debug, Clone, Copy)]
pub(crate) struct AsWritten;

impl Rulebook for AsWritten {
    #[inline(always)]
    fn object(self, _: usize) -> ObjectRules {
        ObjectRules::default()
    }
    #[inline(always)]
    fn light(self, _: usize) -> LightRules {
        LightRules::default()
    }
    #[inline(always)]
    fn epsilon(self, _: usize) -> Option<f64> {
        None
    }
    #[inline(always)]
    fn some(self, _: Kind) -> bool {
        false
    }
    #[inline(always)]
    fn bounces(self) -> usize {
        super::MAX_BOUNCES
    }
    #[inline(always)]
    fn divisor(self) -> Divisor {
        Divisor::Path
    }
    #[inline(always)]
    fn far(self) -> Option<f64> {
        None
    }
    #[inline(always)]
    fn bytes(self) -> Bytes {
        Bytes::Truncate
    }
}

impl Rulebook for &Rules {
    #[inline(always)]
    fn object(self, index: usize) -> ObjectRules {
        self.objects[index]
    }
    #[inline(always)]
    fn light(self, index: usize) -> LightRules {
        self.lights[index]
    }
    #[inline(always)]
    fn epsilon(self, index: usize) -> Option<f64> {
        self.epsilons.as_ref().and_then(|epsilons| epsilons[index])
    }
    #[inline(always)]
    fn some(self, kind: Kind) -> bool {
        self.some.has(kind)
    }
    #[inline(always)]
    fn bounces(self) -> usize {
        self.bounces
    }
    #[inline(always)]
    fn divisor(self) -> Divisor {
        self.divisor
    }
    #[inline(always)]
    fn far(self) -> Option<f64> {
        (self.far < f64::INFINITY).then_some(self.far)
    }
    #[inline(always)]
    fn bytes(self) -> Bytes {
        self.bytes
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_step_s_distance_is_that_to_the_floor_or_the_ceiling() {
        // Against the distances to floor(x) and floor(x) + 1, the nearer one, on values
        // at and a few ulps around every step and every half step, and between them.
        let mut xs = Vec::new();
        for k in 0..256 {
            for base in [k as f64, k as f64 + 0.5, k as f64 + 0.25, k as f64 + 0.999] {
                let mut x = base;
                for _ in 0..4 {
                    xs.extend([x, base - (x - base)]);
                    x = f64::from_bits(x.to_bits() + 1);
                }
            }
        }
        xs.extend([1e-300, 5e-324, 0.5, 0.49999999999999994]);
        for rule in [Bytes::Truncate, Bytes::Round, Bytes::Scale256] {
            let (scale, offset) = match rule {
                Bytes::Round => (255.0, 0.5),
                Bytes::Truncate => (255.0, 0.0),
                Bytes::Scale256 => (256.0, 0.0),
            };
            for &x in xs.iter().filter(|&&x| x > 0.0 && x < 254.5) {
                let channel = (x + offset) / scale;
                let scaled = channel * scale;
                let v = scaled - offset;
                if channel <= 0.0 || v < 0.0 || scaled >= 254.5 {
                    continue;
                }
                let floor = v.floor();
                let expected = (v - floor).min(floor + 1.0 - v);
                assert_eq!(
                    rule.step_distance(channel),
                    Some((expected, scaled)),
                    "{rule:?} {x:e}"
                );
            }
        }
    }

    #[test]
    fn every_id_parses_back_to_its_variant() {
        for variant in Variant::all() {
            assert_eq!(Variant::parse(&variant.id()), Ok(variant));
        }
        let epsilon = Variant {
            value: Some(1e-3),
            ..Variant::of(Kind::ShadowEpsilon)
        };
        assert_eq!(Variant::parse("shadow-epsilon=0.001"), Ok(epsilon));
        assert_eq!(
            Variant::parse("shadow-epsilon=0.001@12"),
            Ok(epsilon.at(12))
        );
        assert_eq!(epsilon.at(12).id(), "shadow-epsilon=0.001@12");
        let hidden = Variant::of(Kind::Hidden).at(7);
        assert_eq!(Variant::parse("hidden@7"), Ok(hidden));
        assert!(Variant::parse("max-dist").is_err());
        assert!(Variant::parse("max-dist=-4").is_err());
        assert!(
            Variant::parse("hidden")
                .unwrap_err()
                .contains("hidden@LINE")
        );
        assert!(
            Variant::parse("upside-down@3")
                .unwrap_err()
                .contains("whole image")
        );
        assert!(Variant::parse("no-shadow@x").is_err());
        assert!(
            Variant::parse("upside")
                .unwrap_err()
                .contains("pixel-centre")
        );
    }

    #[test]
    fn the_table_s_rows_are_in_the_order_of_their_kinds() {
        // `Kind::row` indexes the table by the kind.
        for (index, row) in VARIANTS.iter().enumerate() {
            assert_eq!(row.kind as usize, index, "{}", row.id);
        }
    }

    #[test]
    fn a_byte_s_margin_is_its_distance_to_the_next_step_over_the_channel() {
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
        // 255 × 100.25 / 255 = 100.25 (to a rounding): a quarter level above step 100.
        let margin = Bytes::Truncate.margin(100.25 / 255.0);
        assert!(close(margin, 0.25 / 100.25), "{margin}");
        // Round-bytes steps at 100.5: 100.25 is a quarter below it.
        let margin = Bytes::Round.margin(100.25 / 255.0);
        assert!(close(margin, 0.25 / 100.25), "{margin}");
        // 256 × 0.5 = 128 exactly: on the step.
        assert_eq!(Bytes::Scale256.margin(0.5), 0.0);
        // Above the clamp, the step is at 255: 2 × 255 = 510 is 255 beyond it.
        assert_eq!(Bytes::Truncate.margin(2.0), 0.5);
        // Exactly 0 is 0 in any arithmetic.
        assert_eq!(Bytes::Truncate.margin(0.0), f64::INFINITY);
        // Round-bytes below its first step, 0.5: 0.25 is a quarter away from it.
        assert!(close(Bytes::Round.margin(0.25 / 255.0), 0.25 / 0.25));
        // Fragile where the margin is below the limit: 0.25 / 100.25 is 0.002494.
        assert!(Bytes::Truncate.fragile(100.25 / 255.0, 0.0025));
        assert!(!Bytes::Truncate.fragile(100.25 / 255.0, 0.0024));
        assert!(Bytes::Scale256.fragile(0.5, 1e-12));
        assert!(!Bytes::Truncate.fragile(0.0, 1.0) && !Bytes::Round.fragile(f64::NAN, 1.0));
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
    fn the_saturating_casts_are_the_clamped_formulas() {
        // The rules as the spec writes them: clamp to [0, 1], scale, truncate; NaN 0.
        let written = |rule: Bytes, c: f64| -> u8 {
            if c.is_nan() {
                return 0;
            }
            let c = c.clamp(0.0, 1.0);
            match rule {
                Bytes::Truncate => (c * 255.0).floor() as u8,
                Bytes::Round => (c * 255.0 + 0.5).floor() as u8,
                Bytes::Scale256 => (c * 256.0).min(255.0).floor() as u8,
            }
        };
        // Every step's edges (for 255 and 256 levels) and their neighbours, and what
        // lies outside [0, 1].
        let mut channels = vec![f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -0.0, 1e-300];
        channels.extend([-1.0, -1e-3, 1.0, 1.0 + 1e-9, 2.0, 1e300, -1e300]);
        for k in 0..=256 {
            for scale in [255.0, 256.0] {
                for edge in [f64::from(k) / scale, (f64::from(k) + 0.5) / scale] {
                    channels.extend([edge, edge.next_down(), edge.next_up()]);
                }
            }
        }
        for c in channels {
            for rule in [Bytes::Truncate, Bytes::Round, Bytes::Scale256] {
                assert_eq!(rule.byte(c), written(rule, c), "{rule:?} {c:e}");
            }
        }
    }

    #[test]
    fn tile_parity_copies_only_the_tiled_planes_look() {
        // Two spheres of one material share a look; a tiled plane after them. Under
        // tile-parity the plane's two materials trade places in the varied scene alone,
        // and the spheres keep the look they share with the unvaried scene.
        let m = "1 1 1\n1 1 1\n0 0 0\n";
        let text = format!(
            "8 6\n0 0 3\n13\n{m}0 0 -5\n1\n13\n{m}2 0 -5\n1\n\
             16\n{m}0 1 0\n0 -3 0\n1 0 0\n1 1\n2 2 2\n0 0 0\n0 0 0\n"
        );
        let scene = crate::scene::load(&text).unwrap();
        let options = Options::new(4, 3)
            .with_variant(Variant::of(Kind::TileParity))
            .unwrap();
        let varied = Rules::scene(&options, &scene);
        let shared = |i: usize| Arc::ptr_eq(&scene.objects[i].look, &varied.objects[i].look);
        assert!(shared(0) && shared(1));
        assert!(!shared(2));
        let (before, after) = (&scene.objects[2].look, &varied.objects[2].look);
        assert_eq!(before.material.ambient, DVec3::ONE);
        assert_eq!(after.material.ambient, DVec3::splat(2.0));
    }

    #[test]
    fn two_variants_of_one_rule_conflict() {
        let options = Options::new(4, 3)
            .with_variant(Variant::of(Kind::RoundBytes))
            .unwrap();
        assert!(options.with_variant(Variant::of(Kind::Scale256)).is_err());
        assert!(options.with_variant(Variant::of(Kind::NoDistance)).is_ok());
        let seventy = Variant::of(Kind::MaxDist);
        let far = options.with_variant(seventy).unwrap();
        assert_eq!(far.max_dist, 70.0);
        let fifty = Variant {
            value: Some(50.0),
            ..seventy
        };
        assert!(far.with_variant(fifty).is_err());
        // Scoped to two records, one rule does not conflict; to one record, it does.
        let at = |line| Variant::of(Kind::FlippedNormal).at(line);
        let one = Options::new(4, 3).with_variant(at(4)).unwrap();
        assert!(one.with_variant(at(11)).is_ok());
        assert!(
            one.with_variant(Variant::of(Kind::FacingNormals).at(4))
                .is_err()
        );
        assert!(
            one.with_variant(Variant::of(Kind::FacingNormals).at(11))
                .is_ok()
        );
    }

    #[test]
    fn the_rules_of_scoped_variants_fall_on_their_record_only() {
        let text = "8 6\n0 0 3\n13\n1 1 1\n1 1 1\n0 0 0\n0 0 -3\n1\n\
                    10\n1 1 1\n0 5 0\n13\n1 1 1\n1 1 1\n0 0 0\n2 0 -3\n1\n";
        let scene = crate::load(text).unwrap();
        let options = Options::new(4, 3)
            .with_variant(Variant::of(Kind::NoShadow).at(12))
            .and_then(|o| o.with_variant(Variant::of(Kind::NoLight).at(9)))
            .unwrap();
        let rules = Rules::new(&options, &scene);
        let no_shadow = |i: usize| rules.objects[i].has(Kind::NoShadow);
        assert!(!no_shadow(0) && no_shadow(1));
        assert!(rules.lights[0].has(Kind::NoLight));
        // A line that starts no record of the kind is an error naming those that do.
        let wrong = Options::new(4, 3)
            .with_variant(Variant::of(Kind::ConeScale).at(3))
            .unwrap();
        let error = check_scopes(&wrong, &scene).unwrap_err().to_string();
        assert!(error.contains("line 3 starts a sphere"), "{error}");
        assert!(error.contains("has no cones"), "{error}");
        let light = Options::new(4, 3)
            .with_variant(Variant::of(Kind::NoLight).at(3))
            .unwrap();
        let error = check_scopes(&light, &scene).unwrap_err().to_string();
        assert!(error.contains("the lights start on lines 9"), "{error}");
        assert!(check_scopes(&options, &scene).is_ok());
    }
}
