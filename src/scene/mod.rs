//! Meaning: records to a validated, typed scene (spec §3-§5).
//!
//! [`load`] runs the whole front end: `scene_file` reads the text into records,
//! and as it reads them `build` turns each into a light or an [`Object`], validating its numbers
//! and precomputing everything that depends only on the object (frames, `rotmat`, `irot`,
//! `k`, unit normals, spotlight cosines, textures).

mod build;
pub(crate) mod dump;
mod parallel;

pub use crate::scene_file::MAX_RECORDS;
pub use dump::dump;

use crate::error::SceneError;
use crate::shapes::Shape;
use glam::{DVec2, DVec3};
use std::sync::Arc;

/// Reads and validates a scene, with its texture files from the disk (relative to the
/// current folder); the error points at the line to fix.
pub fn load(text: &str) -> Result<Scene, SceneError> {
    load_with(text, &Disk)
}

/// [`load`] with the texture files (spec §5.8) taken from `files`.
pub fn load_with(text: &str, files: &dyn Files) -> Result<Scene, SceneError> {
    let mut builder = build::Builder::new(files);
    crate::scene_file::read_into(text, &mut builder)
        .and_then(|split| builder.finish(split))
        .map_err(|pending| pending.locate(text))
}

/// [`load_with`] on `threads` threads (0: one per core): the same scene or error, read
/// on every thread where the text is large enough to pay for it (`src/scene/parallel.rs`).
pub fn load_on(text: &str, files: &dyn Files, threads: usize) -> Result<Scene, SceneError> {
    let threads = crate::threads::Threads::new(threads);
    if !parallel::pays(text, &threads) {
        return load_with(text, files);
    }
    let chunks = threads.count() * parallel::CHUNKS_PER_THREAD;
    parallel::load_in_chunks(text, files, &threads, chunks).map_err(|pending| pending.locate(text))
}

/// [`load_with`] as [`load_on`] reads a large text, whatever its size: in `chunks`
/// chunks on `threads` threads. For the tests and the fuzzer, which check that it gives
/// what [`load_with`] gives.
#[doc(hidden)]
pub fn load_in_chunks(
    text: &str,
    files: &dyn Files,
    threads: usize,
    chunks: usize,
) -> Result<Scene, SceneError> {
    let threads = crate::threads::Threads::new(threads);
    parallel::load_in_chunks(text, files, &threads, chunks).map_err(|pending| pending.locate(text))
}

/// Where the texture files a scene names come from; shared by the threads that read a
/// large scene ([`load_on`]).
pub trait Files: Sync {
    /// The file a scene names (as written there), or why it cannot be read, in the words
    /// of [`Disk`] so that a missing file reads the same everywhere.
    fn open(&self, name: &str) -> Result<Box<dyn std::io::BufRead + '_>, String>;
}

/// Files on the disk, as the command line reads them.
pub struct Disk;

impl Files for Disk {
    fn open(&self, name: &str) -> Result<Box<dyn std::io::BufRead + '_>, String> {
        // A FIFO or a device would block the load or never end; only a file is a texture.
        if !std::fs::metadata(name)
            .map_err(|e| e.to_string())?
            .is_file()
        {
            return Err("it is not a regular file".into());
        }
        let file = std::fs::File::open(name).map_err(|e| e.to_string())?;
        Ok(Box::new(std::io::BufReader::new(file)))
    }
}

/// Files given by name with their bytes, as a user adds them to the web page.
pub type InMemory = std::collections::BTreeMap<String, Vec<u8>>;

/// What [`Disk`] says of a file that is not there (Linux's message for ENOENT), so
/// that the web page's error for a texture the user has not added is the command line's.
pub const NOT_FOUND: &str = "No such file or directory (os error 2)";

impl Files for InMemory {
    fn open(&self, name: &str) -> Result<Box<dyn std::io::BufRead + '_>, String> {
        match self.get(name) {
            Some(bytes) => Ok(Box::new(bytes.as_slice())),
            None => Err(NOT_FOUND.to_string()),
        }
    }
}

/// Ambient, diffuse and specular rgb (spec §3.1). Unbounded reals; the specular triple is
/// the mirror reflectivity (spec §4.5).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Light the surface shows by itself, before the distance division.
    pub ambient: DVec3,
    /// How strongly it scatters each light (spec §4.3).
    pub diffuse: DVec3,
    /// Mirror reflectivity per channel.
    pub specular: DVec3,
}

/// A spotlight's beam (spec §4.3, §5.7).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Beam {
    /// unit(aim - location).
    pub direction: DVec3,
    /// The half-angle in degrees, as written.
    pub half_angle: f64,
    /// cos(half-angle): a point is lit only if its direction's cosine exceeds this.
    pub cos_limit: f64,
}

/// A point light (10) or spotlight (11). Lights are invisible.
#[derive(Debug, Clone, PartialEq)]
pub struct Light {
    /// Emissivity rgb.
    pub emissivity: DVec3,
    /// Where the light is; it shines in every direction (a spotlight within its beam).
    pub location: DVec3,
    /// The beam of a spotlight; `None` for a point light.
    pub beam: Option<Beam>,
    /// The line of its type code.
    pub line: usize,
}

/// The procedural shaders of spec §5.5.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shader {
    /// Index 0: red or blue removed in stripes.
    Stripes,
    /// Index 1: the ambient modulated by a colour wheel around the origin.
    ColourWheel,
}

/// How a textured plane maps its texture (spec §5.8).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TextureMode {
    /// 1: stretched once over the rectangle.
    Fit,
    /// 2: repeated at its own size in screen pixels.
    Tile,
}

/// A P6 texture as bytes, rows from the **bottom** up so that row 0 is y = 0 on the plane.
#[derive(Debug, Clone, PartialEq)]
pub struct Texture {
    /// The file name as written in the scene.
    pub path: String,
    /// Width in texels.
    pub width: usize,
    /// Height in texels.
    pub height: usize,
    /// RGB bytes, `width * height`, bottom row first.
    pub texels: Vec<[u8; 3]>,
}

/// What varies a material over a surface.
#[derive(Debug, Clone, PartialEq)]
pub enum Pattern {
    /// One material everywhere.
    Plain,
    /// 16: a checkerboard of the material and a background material (spec §5.4).
    Tiles {
        /// Tile width and height, > 0.
        tile: DVec2,
        /// The second material block; boxed, so that every other object does not carry
        /// its 72 bytes (a pattern is as large as its largest kind).
        background: Box<Material>,
    },
    /// 17: a texture multiplying ambient and diffuse (spec §5.8).
    Texture {
        /// The texture, shared if the scene is cloned.
        texture: Arc<Texture>,
        /// How the texture covers the rectangle: stretched once (fit) or repeated (tile).
        mode: TextureMode,
        /// The rectangle's width and height, over which fit mode stretches the texture.
        size: DVec2,
    },
    /// 19, 20: a shader replacing the ambient (spec §5.5).
    Shader {
        /// The shader the record's index names.
        shader: Shader,
        /// The sphere's centre or the plane's point: the shader's origin.
        origin: DVec3,
    },
}

/// What a surface looks like: its material and how the material varies over it.
#[derive(Debug, Clone, PartialEq)]
pub struct Look {
    /// The material (for tiled planes, the foreground tiles').
    pub material: Material,
    /// Tiles, texture, shader or nothing.
    pub pattern: Pattern,
}

/// A visible object: a shape and its look, 88 bytes whatever its kind (a million
/// records must fit a laptop's memory).
#[derive(Debug, Clone, PartialEq)]
pub struct Object {
    /// The geometry: what a ray hits and the normal there.
    pub shape: Shape,
    /// Its material and pattern, shared with the record before when the two are the same
    /// plain material (a generated scene's thousand spheres of one colour hold one copy).
    /// A scoped variant that changes it changes only its own copy (`Arc::make_mut`).
    pub look: Arc<Look>,
    /// The line of its type code.
    pub line: usize,
}

impl Object {
    /// The record's name: "sphere", "tiled plane", ...: its type code's, which the shape
    /// and the pattern tell (a shader makes a sphere or plane 19 or 20, a texture makes a
    /// finite plane 17).
    pub fn kind(&self) -> &'static str {
        use crate::scene_file::layout;
        let shaded = matches!(self.look.pattern, Pattern::Shader { .. });
        let code = match &self.shape {
            Shape::Sphere(_) if shaded => 19,
            Shape::Sphere(_) => 13,
            Shape::Plane(_) if shaded => 20,
            Shape::Plane(_) => 14,
            Shape::FinitePlane(_) if matches!(self.look.pattern, Pattern::Texture { .. }) => 17,
            Shape::FinitePlane(_) => 15,
            Shape::TiledPlane(_) => 16,
            Shape::Paraboloid(_) => 21,
            Shape::Cylinder(_) => 22,
            Shape::Cone(_) => 23,
            Shape::Hyperboloid(_) => 24,
            Shape::Quadric(_) => return layout::QUADRIC.name,
        };
        layout::of_code(code).map_or(layout::QUADRIC.name, |layout| layout.name)
    }

    /// Whether a mirror ray may leave it (spec §4.5): a specular that is not zero in
    /// its material, or in a tiled plane's background (a texture or a shader keeps the
    /// material's).
    pub fn reflects(&self) -> bool {
        let mirror = |m: &Material| m.specular != DVec3::ZERO;
        mirror(&self.look.material)
            || matches!(&self.look.pattern, Pattern::Tiles { background, .. } if mirror(background))
    }
}

/// A validated scene: header, lights and objects, each in file order.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// World window width and height, centred on the origin in z = 0 (spec §2.1).
    pub window: DVec2,
    /// The eye: every camera ray starts here (spec §4.1).
    pub viewpoint: DVec3,
    /// Lights in file order.
    pub lights: Vec<Light>,
    /// Objects in file order (the order that breaks ties, spec §4.6).
    pub objects: Vec<Object>,
}

impl Scene {
    /// The default image size of spec §1: width 640, height from the window's aspect
    /// ratio, rounded.
    pub fn default_size(&self) -> (u64, u64) {
        (640, self.height_for(640))
    }

    /// The height of a `width`-pixel image with the window's aspect ratio, rounded (spec
    /// §1), at most `u32::MAX`.
    pub fn height_for(&self, width: u64) -> u64 {
        let height = (width as f64 * self.window.y / self.window.x).round();
        height.clamp(0.0, u32::MAX as f64) as u64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_objects_kind_is_its_records_name() {
        // One record of every object code, each named by the reader's layout table; the
        // object's kind is derived from its shape and pattern instead.
        let m = "1 1 1\n1 1 1\n0 0 0\n";
        let records = [
            format!("13\n{m}0 0 -5\n1\n"),
            format!("14\n{m}0 1 0\n0 -2 0\n"),
            format!("15\n{m}0 0 1\n0 0 -9\n1 0 0\n2 2\n"),
            format!("16\n{m}0 1 0\n0 -3 0\n1 0 0\n1 1\n{m}"),
            format!("17\n{m}0 0 1\n0 0 -9\n1 0 0\n2 2\nt.ppm\n1\n"),
            format!("19\n{m}0 0 -5\n1\n0\n"),
            format!("20\n{m}0 1 0\n0 -2 0\n1\n"),
            format!("21\n{m}0 0 -5\n0 1 0\n1 1\n"),
            format!("22\n{m}0 0 -5\n0 1 0\n1 1\n"),
            format!("23\n{m}0 0 -5\n0 1 0\n1 1\n"),
            format!("24\n{m}0 0 -5\n0 1 0\n1 1\n0.5\n"),
            format!("QUADRIC 1 0 0 0 1 0 0 1 0 -1\n{m}"),
        ];
        let text = format!("8 6\n0 0 3\n{}", records.concat());
        let files = InMemory::from([("t.ppm".to_string(), b"P6\n1 1\n255\n\x10\x20\x30".to_vec())]);
        let scene = load_with(&text, &files).unwrap();
        let read = crate::scene_file::read(&text).unwrap();
        let names: Vec<&str> = read.records.iter().map(|r| r.layout.name).collect();
        let kinds: Vec<&str> = scene.objects.iter().map(Object::kind).collect();
        assert_eq!(kinds, names);
        assert_eq!(kinds.len(), 12);
    }

    #[test]
    fn a_syntax_error_anywhere_comes_before_an_earlier_records_meaning_error() {
        // Record 1 has radius 0 (a meaning error); record 2 has a word for a number. The
        // builder works while the reader reads, but the syntax error is still reported.
        let bad_radius = "13\n1 1 1\n0 0 0\n0 0 0\n0 0 -3\n0\n";
        let bad_word = "13\n1 1 1\n0 0 zero\n0 0 0\n0 0 -3\n1\n";
        let error = load(&format!("8 6\n0 0 3\n{bad_radius}{bad_word}")).unwrap_err();
        assert_eq!(error.at.line, 11, "{error}");
        let error = load(&format!("8 6\n0 0 3\n{bad_radius}")).unwrap_err();
        assert_eq!(error.at.line, 8, "{error}");
    }

    #[test]
    fn a_missing_number_is_named_even_when_the_error_shows_up_later() {
        // The ambient line lacks a number; scanf takes the diffuse line's first number, the
        // centre takes the next record's code, and the radius (line 11) is 0.
        let text = "8 6\n0 0 3\n13\n1 2\n0 0 0\n0 0 0\n0 0 -3\n1\n13\n1 1 1\n0 0 0\n";
        let error = load(text).unwrap_err();
        let split = "the sphere's ambient line (line 4) holds only 2 of its 3 numbers";
        assert!(
            error.notes.iter().any(|n| n.starts_with(split)),
            "{error:?}"
        );
    }
}
