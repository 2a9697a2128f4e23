//! What an image is computed with, as the command line's shared options (and the web
//! page's controls) name it: the choices behind an [`Options`], and the flags that
//! reproduce them.

use super::variant::ChoiceError;
use super::{DEFAULT_MAX_DIST, Options, Show, Stage, Variant};
use crate::scene::Scene;
use crate::shapes::kernel::KernelChoice;

/// `--max-dist`, `--kernel`, `--stage`, `--show` and `--variant`.
#[derive(Debug, Clone, PartialEq)]
pub struct Choices {
    /// Paths of rays longer than this are black (spec §4.2).
    pub max_dist: f64,
    /// How hit distances are computed.
    pub kernel: KernelChoice,
    /// The course's assignment (spec §7.2).
    pub stage: Stage,
    /// A diagnostic image instead of the stage's.
    pub show: Option<Show>,
    /// The students' mistakes rendered (spec §7.3), in the order given.
    pub variants: Vec<Variant>,
}

impl Default for Choices {
    fn default() -> Choices {
        Choices {
            max_dist: DEFAULT_MAX_DIST,
            kernel: KernelChoice::Accurate,
            stage: Stage::Full,
            show: None,
            variants: Vec::new(),
        }
    }
}

/// The item of `all` whose `name` is `name`, or "expected one of: …" listing the names:
/// how `--stage`, `--show` and `--kernel` (and the web page's controls) read a name.
pub fn by_name<T: Copy>(
    all: &[T],
    name: &str,
    of: impl Fn(T) -> &'static str,
) -> Result<T, String> {
    match all.iter().find(|&&item| of(item) == name) {
        Some(&item) => Ok(item),
        None => {
            let names: Vec<_> = all.iter().map(|&item| of(item)).collect();
            Err(format!("expected one of: {}", names.join(", ")))
        }
    }
}

/// Why a `width` x `height` image cannot be rendered, if it cannot: smaller than 2x2, or
/// more than `max_pixels`.
pub fn size_problem(width: u64, height: u64, max_pixels: u64) -> Option<String> {
    if width < 2 || height < 2 {
        Some(format!(
            "the image must be at least 2x2 pixels (the projection divides by W-1 and H-1), \
             not {width}x{height}"
        ))
    } else if width.saturating_mul(height) > max_pixels {
        Some(format!(
            "{width}x{height} is more than the {max_pixels} pixels this program renders"
        ))
    } else {
        None
    }
}

impl Choices {
    /// Fails on a choice no render can take, before any scene is read.
    pub fn check(&self) -> Result<(), ChoiceError> {
        if self.max_dist.is_nan() || self.max_dist <= 0.0 {
            return Err(ChoiceError::MaxDist(self.max_dist));
        }
        Ok(())
    }

    /// The options for a `width` x `height` render of `scene` (one thread), or why the
    /// choices cannot go together (two variants replacing one rule) or cannot apply to
    /// the scene (a variant scoped to a line that starts no record of its kind).
    pub fn options(
        &self,
        scene: &Scene,
        width: usize,
        height: usize,
    ) -> Result<Options, ChoiceError> {
        self.check()?;
        let options = Options {
            max_dist: self.max_dist,
            kernel: self.kernel,
            stage: self.stage,
            show: self.show,
            ..Options::new(width, height)
        };
        let options = options.with_variants(&self.variants)?;
        super::variant::check_scopes(&options, scene)?;
        Ok(options)
    }

    /// The command-line flags that make these choices, each with a leading space; empty
    /// for the defaults.
    pub fn flags(&self) -> String {
        let mut flags = String::new();
        if self.max_dist != DEFAULT_MAX_DIST {
            flags += &format!(" --max-dist {}", self.max_dist);
        }
        if self.kernel != KernelChoice::Accurate {
            flags += &format!(" --kernel {}", self.kernel.name());
        }
        if let Some(show) = self.show {
            flags += &format!(" --show {}", show.name());
        } else if self.stage != Stage::Full {
            flags += &format!(" --stage {}", self.stage.name());
        }
        if !self.variants.is_empty() {
            let ids: Vec<_> = self.variants.iter().map(|v| v.id()).collect();
            flags += &format!(" --variant {}", ids.join(","));
        }
        flags
    }
}
