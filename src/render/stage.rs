//! The stages of spec §7.2 (the course's assignments) and the diagnostic images that
//! replace a stage's colour.

/// How much of spec §4 applies: the course's assignments, in the order it taught them
/// (spec §7.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Stage {
    /// §4.2 without the lights (step 5) and the reflection (step 7).
    Ambient,
    /// Ambient and every light's §4.3 contribution, without the shadow test.
    Diffuse,
    /// Ambient and diffuse with the shadow test; no reflection.
    Shadows,
    /// Spec §4 as written: the finished image.
    #[default]
    Full,
}

impl Stage {
    /// Every stage, in the course's order.
    pub const ALL: [Stage; 4] = [Stage::Ambient, Stage::Diffuse, Stage::Shadows, Stage::Full];

    /// The name `--stage` takes.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Ambient => "ambient",
            Stage::Diffuse => "diffuse",
            Stage::Shadows => "shadows",
            Stage::Full => "full",
        }
    }

    /// Whether the lights' diffuse terms are added.
    #[inline(always)]
    pub fn lights(self) -> bool {
        self != Stage::Ambient
    }

    /// Whether a shadow ray can block a light.
    #[inline(always)]
    pub fn shadows(self) -> bool {
        matches!(self, Stage::Shadows | Stage::Full)
    }

    /// Whether mirrors reflect.
    #[inline(always)]
    pub fn reflects(self) -> bool {
        self == Stage::Full
    }
}

/// A diagnostic image instead of the stage's: what a student reaches for when stuck.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Show {
    /// The unit normal at the first hit as a colour, (N + 1) / 2.
    Normals,
    /// Each object in its own colour ([`super::object_colour`]).
    Objects,
    /// Grey 1 - t / MAX_DIST for the distance t to the first hit.
    Depth,
}

impl Show {
    /// Every diagnostic image.
    pub const ALL: [Show; 3] = [Show::Normals, Show::Objects, Show::Depth];

    /// The name `--show` takes.
    pub fn name(self) -> &'static str {
        match self {
            Show::Normals => "normals",
            Show::Objects => "objects",
            Show::Depth => "depth",
        }
    }
}
