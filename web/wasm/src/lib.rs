//! The WebAssembly binding of `legacy-rt` for the page under `web/`: load a scene (with
//! the texture files the user added), render it as RGBA for a canvas, trace a pixel,
//! compare a student's image. Every result is the library's, with the command line's
//! words; this crate only converts between it and what JavaScript can hold.
//!
//! The page calls it from a Web Worker (`web/worker.js`), so a long render never blocks
//! the page, and cancelling one is ending the worker.

use legacy_rt::compare::{self, Settings, Tolerance, Verdict};
use legacy_rt::render::{Choices, Show, Stage, Trace, Variant, by_name, size_problem};
use legacy_rt::scene::{Files, InMemory, NOT_FOUND};
use legacy_rt::shapes::kernel::KernelChoice;
use legacy_rt::{Image, Options, Scene, SceneError};
use serde::{Deserialize, Serialize};
use wasm_bindgen::prelude::*;

/// The largest image the page renders, in pixels (4096²): a page's WebAssembly memory
/// holds the image twice (RGB and the canvas's RGBA), 112 MB at this size; the command
/// line renders up to 2^28.
const MAX_PIXELS: u64 = 1 << 24;

/// The choices of the page's controls, as JSON: the command line's option values, by
/// its names (`{"stage": "diffuse", "variants": "no-shadows,upside-down"}`).
#[derive(Deserialize, Default)]
#[serde(default, deny_unknown_fields)]
struct ChoicesJson {
    max_dist: Option<f64>,
    kernel: Option<String>,
    stage: Option<String>,
    show: Option<String>,
    variants: Option<String>,
}

/// The page's choices, checked as the command line checks its options.
fn choices(json: &str) -> Result<Choices, String> {
    let given: ChoicesJson = match json.trim() {
        "" => ChoicesJson::default(),
        json => serde_json::from_str(json).map_err(|error| format!("the choices: {error}"))?,
    };
    let mut choices = Choices::default();
    if let Some(max_dist) = given.max_dist {
        choices.max_dist = max_dist;
    }
    if let Some(kernel) = given.kernel.as_deref() {
        choices.kernel = by_name(&KernelChoice::ALL, kernel, KernelChoice::name)
            .map_err(|error| format!("--kernel: {error}"))?;
    }
    if let Some(stage) = given.stage.as_deref() {
        choices.stage = by_name(&Stage::ALL, stage, Stage::name)
            .map_err(|error| format!("--stage: {error}"))?;
    }
    if let Some(show) = given.show.as_deref().filter(|show| !show.is_empty()) {
        let show =
            by_name(&Show::ALL, show, Show::name).map_err(|error| format!("--show: {error}"))?;
        choices.show = Some(show);
    }
    for id in given.variants.iter().flat_map(|ids| ids.split(',')) {
        let id = id.trim();
        if !id.is_empty() {
            let variant = Variant::parse(id).map_err(|error| format!("--variant {id}: {error}"))?;
            choices.variants.push(variant);
        }
    }
    choices.check().map_err(|error| error.to_string())?;
    Ok(choices)
}

/// A message for JavaScript, thrown as an `Error`.
fn thrown(message: impl std::fmt::Display) -> JsError {
    JsError::new(&message.to_string())
}

/// A scene's load error, as the page shows it: the command line's message, and the line
/// and column to highlight.
#[derive(Serialize)]
struct LoadError {
    message: String,
    line: usize,
    column: usize,
}

impl From<SceneError> for LoadError {
    fn from(error: SceneError) -> LoadError {
        LoadError {
            line: error.at.line,
            column: error.at.column,
            message: error.to_string(),
        }
    }
}

/// What the page knows of a loaded scene.
#[derive(Serialize)]
struct Loaded {
    width: u64,
    height: u64,
    lights: usize,
    objects: usize,
}

/// The texture files the user added. A browser has no folders: a scene's
/// `textures/wood.ppm` is the added file of that name, or else the one added as
/// `wood.ppm`; any other name is missing, with the command line's message.
struct Added(InMemory);

impl Files for Added {
    fn open(&self, name: &str) -> Result<Box<dyn std::io::BufRead + '_>, String> {
        let base = name.rsplit(['/', '\\']).next().unwrap_or(name);
        match self.0.get(name).or_else(|| self.0.get(base)) {
            Some(bytes) => Ok(Box::new(bytes.as_slice())),
            None => Err(NOT_FOUND.to_string()),
        }
    }
}

/// A scene, the texture files it may name, and the last image rendered of it.
#[wasm_bindgen]
pub struct Session {
    files: Added,
    scene: Option<Scene>,
    image: Option<Image>,
}

impl Default for Session {
    fn default() -> Self {
        Self::new()
    }
}

#[wasm_bindgen]
impl Session {
    /// A session with no scene and no files.
    #[wasm_bindgen(constructor)]
    pub fn new() -> Session {
        Session {
            files: Added(InMemory::new()),
            scene: None,
            image: None,
        }
    }

    /// Adds (or replaces) a file a scene may name as its texture, under that name.
    pub fn add_file(&mut self, name: &str, bytes: Vec<u8>) {
        self.files.0.insert(name.to_string(), bytes);
    }

    /// The files added, by name, as a JSON list.
    pub fn file_names(&self) -> String {
        let names: Vec<_> = self.files.0.keys().collect();
        serde_json::to_string(&names).unwrap_or_default()
    }

    /// Loads the scene text. Returns JSON: `{"ok": {"width", "height", "lights",
    /// "objects"}}` with the default image size, or `{"error": {"message", "line",
    /// "column"}}` with the command line's message.
    pub fn load(&mut self, text: &str) -> String {
        self.image = None;
        let result = match legacy_rt::load_with(text, &self.files) {
            Ok(scene) => {
                let (width, height) = scene.default_size();
                let loaded = Loaded {
                    width,
                    height,
                    lights: scene.lights.len(),
                    objects: scene.objects.len(),
                };
                self.scene = Some(scene);
                serde_json::json!({ "ok": loaded })
            }
            Err(error) => {
                self.scene = None;
                serde_json::json!({ "error": LoadError::from(error) })
            }
        };
        result.to_string()
    }

    /// The reference's trace of the pixel in column `x` and canvas row `row` (0 at the
    /// top) of a render with `options`.
    fn pixel(&self, options: &Options, x: u32, row: u32) -> Result<Trace, JsError> {
        let (x, y) = self.at(options, x, row)?;
        legacy_rt::render::trace(self.scene()?, options, x, y)
            .ok_or_else(|| thrown("the pixel is outside the image"))
    }

    /// The pixel (x, y), (0, 0) at the lower left, in column `x` and canvas row `row`.
    fn at(&self, options: &Options, x: u32, row: u32) -> Result<(usize, usize), JsError> {
        let (w, h) = (options.width, options.height);
        let (x, row) = (x as usize, row as usize);
        if x >= w || row >= h {
            return Err(thrown(format!(
                "column {x}, row {row} is outside the {w}x{h} image"
            )));
        }
        // The row map is its own inverse: it gives the pixel row a canvas row shows.
        Ok((x, options.row_of(row)))
    }

    fn scene(&self) -> Result<&Scene, JsError> {
        self.scene
            .as_ref()
            .ok_or_else(|| thrown("no scene is loaded"))
    }

    /// The options of a `width` x `height` render with the page's choices (JSON), and
    /// those choices; a height of 0 means the one the world window gives for that width.
    fn options(
        &self,
        width: u32,
        height: u32,
        choices_json: &str,
    ) -> Result<(Options, Choices), JsError> {
        let scene = self.scene()?;
        let (width, height) = (u64::from(width), u64::from(height));
        let height = match height {
            0 => scene.height_for(width),
            h => h,
        };
        if let Some(problem) = size_problem(width, height, MAX_PIXELS) {
            let limits = match width.saturating_mul(height) > MAX_PIXELS {
                true => "; the page renders up to 4096x4096, the command line up to 16384x16384",
                false => "",
            };
            return Err(thrown(format!("{problem}{limits}")));
        }
        let choices = choices(choices_json).map_err(thrown)?;
        let options = (choices.options(scene, width as usize, height as usize)).map_err(thrown)?;
        Ok((options, choices))
    }

    /// Renders the loaded scene; the image, rows top to bottom, as RGBA for a canvas's
    /// `ImageData` (alpha 255). It is kept for [`Session::png`] and [`Session::ppm`].
    pub fn render(&mut self, width: u32, height: u32, choices: &str) -> Result<Vec<u8>, JsError> {
        let (options, _) = self.options(width, height, choices)?;
        let image = legacy_rt::render(self.scene()?, &options, |_| {});
        let rgba = rgba(&image);
        self.image = Some(image);
        Ok(rgba)
    }

    /// The last image rendered, as PNG.
    pub fn png(&self) -> Result<Vec<u8>, JsError> {
        let image = self
            .image
            .as_ref()
            .ok_or_else(|| thrown("nothing rendered"))?;
        legacy_rt::image_output::png(image).map_err(thrown)
    }

    /// The last image rendered, as binary PPM (the course program's output).
    pub fn ppm(&self) -> Result<Vec<u8>, JsError> {
        let image = self
            .image
            .as_ref()
            .ok_or_else(|| thrown("nothing rendered"))?;
        Ok(legacy_rt::image_output::ppm(image))
    }

    /// The trace of the pixel in column `x` and canvas row `row` (0 at the top) of a
    /// `width` x `height` render, as `legacy-rt trace X Y` prints it for that pixel:
    /// `format` is "readable" or "course". JSON: `{"x", "y", "text", "bytes", "command"}`,
    /// with the pixel's (x, y), (0, 0) at the lower left, and the `trace` command line
    /// for the scene file `scene_name`.
    #[allow(clippy::too_many_arguments)]
    pub fn trace(
        &self,
        x: u32,
        row: u32,
        width: u32,
        height: u32,
        choices_json: &str,
        format: &str,
        scene_name: &str,
    ) -> Result<String, JsError> {
        let (options, chosen) = self.options(width, height, choices_json)?;
        let trace = self.pixel(&options, x, row)?;
        let scene = self.scene()?;
        let (x, y) = trace.pixel;
        let text = match format {
            "course" => trace.course(scene),
            _ => trace.readable(scene),
        };
        let command = compare::text::trace_command(&chosen, &options, scene_name, x, y, &[]);
        let traced = serde_json::json!({
            "x": x,
            "y": y,
            "text": text,
            "bytes": trace.bytes,
            "command": command,
        });
        Ok(traced.to_string())
    }

    /// The student's own debug trace (`student`, the text of the file `file_name`) read
    /// against the reference's trace of the pixel in column `x` and canvas row `row`, as
    /// `legacy-rt trace X Y W H --against FILE` reads it. JSON: `trace --against --json`'s
    /// keys and `text`, the report the command prints. A trace that cannot be read
    /// against this pixel (another pixel, size or scene; no DBG_ line) is an error with
    /// the command's message.
    #[allow(clippy::too_many_arguments)]
    pub fn against(
        &self,
        x: u32,
        row: u32,
        width: u32,
        height: u32,
        choices_json: &str,
        file_name: &str,
        student: &str,
    ) -> Result<String, JsError> {
        let (options, _) = self.options(width, height, choices_json)?;
        let scene = self.scene()?;
        let (x, y) = self.at(&options, x, row)?;
        let shown = legacy_rt::error::escaped(file_name);
        let read = legacy_rt::render::tracing(scene, &options, |frame| {
            legacy_rt::against::against(scene, frame, (x, y), student.as_bytes())
        });
        let (report, trace) = read.map_err(|unreadable| thrown(unreadable.about(&shown)))?;
        let size = (options.width, options.height);
        let mut json = serde_json::to_value(report.summary(size, file_name))
            .map_err(|error| thrown(error.to_string()))?;
        json["text"] = report.text(scene, &trace, &shown).into();
        Ok(json.to_string())
    }

    /// Every pixel of the student's own debug trace read against the reference, as
    /// `legacy-rt trace --against FILE W H` reads it: JSON with its `--json` keys
    /// (`pixels`, `agree`, `differ`, `groups` each with its `pixel`, ...), `agrees`,
    /// and `text`, the report the command prints.
    pub fn against_all(
        &self,
        width: u32,
        height: u32,
        choices_json: &str,
        file_name: &str,
        student: &str,
    ) -> Result<String, JsError> {
        let (options, chosen) = self.options(width, height, choices_json)?;
        let scene = self.scene()?;
        let shown = legacy_rt::error::escaped(file_name);
        let read = legacy_rt::render::tracing(scene, &options, |frame| {
            legacy_rt::against::whole(scene, frame, student.as_bytes())
        });
        let report = read.map_err(|unreadable| thrown(unreadable.about(&shown)))?;
        let (w, h) = (options.width, options.height);
        let flags = chosen.flags();
        let word = compare::text::shell_word(file_name);
        let command = |x: usize, y: usize| {
            format!("legacy-rt trace {x} {y} {w} {h}{flags} --against {word} < scene.txt")
        };
        let mut json = serde_json::to_value(&report).map_err(|error| thrown(error.to_string()))?;
        json["agrees"] = report.agrees().into();
        json["text"] = report.text(&shown, command).into();
        // Each group's pixel's canvas row, for the page to trace it.
        for (group, value) in report
            .groups
            .iter()
            .zip(json["groups"].as_array_mut().into_iter().flatten())
        {
            value["row"] = options.row_of(group.pixel.1).into();
        }
        Ok(json.to_string())
    }

    /// The canvas row that shows pixel row `y` (0 at the bottom) of a `width` x `height`
    /// render with the page's choices: what the page traces for an X and Y typed in.
    pub fn row(&self, width: u32, height: u32, choices_json: &str, y: u32) -> Result<u32, JsError> {
        let (options, _) = self.options(width, height, choices_json)?;
        let y = y as usize;
        if y >= options.height {
            return Err(thrown(format!(
                "Y must be below {}, the image's height ((0, 0) is the lower-left pixel)",
                options.height
            )));
        }
        Ok(options.row_of(y) as u32)
    }

    /// Compares the student's image (`bytes` of a PPM or PNG file named `name`) with the
    /// loaded scene's reference at the student image's size, as `legacy-rt compare
    /// SCENE STUDENT` does with `--tolerance levels --allow percent` and, if asked,
    /// `--diagnose`; the report calls the scene file `scene`.
    #[allow(clippy::too_many_arguments)]
    pub fn compare(
        &self,
        scene_name: &str,
        name: &str,
        bytes: &[u8],
        choices_json: &str,
        levels: u8,
        percent: f64,
        diagnose: bool,
    ) -> Result<Comparison, JsError> {
        let scene = self.scene()?;
        let name = legacy_rt::error::escaped(name);
        let reader = std::io::Cursor::new(bytes);
        let student = compare::read::image_named(reader, MAX_PIXELS, &name, "student's image")
            .map_err(thrown)?;
        let (width, height) = (student.width as u32, student.height as u32);
        let (options, chosen) = self.options(width, height, choices_json)?;
        let precision = Tolerance::default().precision;
        let reference = compare::reference(scene, &options, &student, precision, diagnose);
        let settings = Settings {
            tolerance: Tolerance {
                levels,
                allow: percent / 100.0,
                precision,
            },
            worst: 10,
            diagnose,
        };
        let with_scene = Some((scene, &options));
        let mut report =
            compare::report(&reference, &student, with_scene, &settings).map_err(thrown)?;
        report.add_trace_commands(|x, y, under| {
            compare::text::trace_command(&chosen, &options, scene_name, x, y, under)
        });
        let text = compare::text::text(&report, scene_name, &name, Some(&chosen));
        let diff = compare::diff_image(&reference, &student, levels).map_err(thrown)?;
        Ok(Comparison {
            json: serde_json::to_string_pretty(&report).map_err(thrown)?,
            text,
            matches: report.verdict == Verdict::Match,
            diff: rgba(&diff),
            width: diff.width as u32,
            height: diff.height as u32,
        })
    }
}

/// A comparison's report, as text and as `--json`, and its diff image.
#[wasm_bindgen]
pub struct Comparison {
    json: String,
    text: String,
    matches: bool,
    diff: Vec<u8>,
    width: u32,
    height: u32,
}

#[wasm_bindgen]
impl Comparison {
    /// The report as `legacy-rt compare --json` prints it.
    pub fn json(&self) -> String {
        self.json.clone()
    }

    /// The report as `legacy-rt compare` prints it.
    pub fn text(&self) -> String {
        self.text.clone()
    }

    /// Whether the images match within the tolerance (exit status 0).
    pub fn matches(&self) -> bool {
        self.matches
    }

    /// The diff image as RGBA: the reference in grey where the pixels match, differing
    /// pixels blue, yellow or red.
    pub fn diff(&self) -> Vec<u8> {
        self.diff.clone()
    }

    /// The diff image's width.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// The diff image's height.
    pub fn height(&self) -> u32 {
        self.height
    }
}

/// The image's bytes as RGBA, alpha 255.
fn rgba(image: &Image) -> Vec<u8> {
    let mut bytes = Vec::with_capacity(image.pixels.len() * 4);
    for &[r, g, b] in &image.pixels {
        bytes.extend_from_slice(&[r, g, b, 255]);
    }
    bytes
}

/// What the page's controls offer, as JSON: `{"stages", "shows", "kernels",
/// "variants": [{"id", "about"}]}`, from the library's own lists.
#[wasm_bindgen]
pub fn vocabulary() -> String {
    let variants: Vec<_> = Variant::all()
        .map(|variant| serde_json::json!({ "id": variant.id(), "about": variant.describe() }))
        .collect();
    let names = |names: Vec<&str>| serde_json::json!(names);
    serde_json::json!({
        "stages": names(Stage::ALL.iter().map(|s| s.name()).collect()),
        "shows": names(Show::ALL.iter().map(|s| s.name()).collect()),
        "kernels": names(KernelChoice::ALL.iter().map(|k| k.name()).collect()),
        "variants": variants,
    })
    .to_string()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Read;

    #[test]
    fn an_added_file_is_found_by_its_path_or_its_name() {
        let mut added = Added(InMemory::new());
        added.0.insert("wood.ppm".into(), b"P6".to_vec());
        added.0.insert("textures/stone.ppm".into(), b"P3".to_vec());
        let read = |name: &str| {
            let mut text = String::new();
            let mut file = added.open(name)?;
            file.read_to_string(&mut text).map_err(|e| e.to_string())?;
            Ok::<_, String>(text)
        };
        assert_eq!(read("examples/textures/wood.ppm").unwrap(), "P6");
        assert_eq!(read("wood.ppm").unwrap(), "P6");
        assert_eq!(read("textures/stone.ppm").unwrap(), "P3");
        assert_eq!(read("stone.ppm").unwrap_err(), NOT_FOUND);
        assert_eq!(read("c:\\course\\wood.ppm").unwrap(), "P6");
    }

    #[test]
    fn choices_are_the_command_lines() {
        let chosen = choices(r#"{"stage": "diffuse", "variants": "no-shadows, upside-down"}"#);
        let chosen = chosen.unwrap();
        assert_eq!(chosen.stage, Stage::Diffuse);
        assert_eq!(
            chosen.flags(),
            " --stage diffuse --variant no-shadows,upside-down"
        );
        let error = choices(r#"{"stage": "final"}"#).err().unwrap();
        assert_eq!(
            error,
            "--stage: expected one of: ambient, diffuse, shadows, full"
        );
        assert!(choices(r#"{"max_dist": 0}"#).is_err());
        assert!(choices(r#"{"colour": 1}"#).is_err());
    }

    #[test]
    fn a_students_trace_is_read_as_the_command_line_reads_it() {
        let mut session = Session::new();
        let loaded = session.load(include_str!("../../../examples/studio.txt"));
        assert!(loaded.starts_with(r#"{"ok""#), "{loaded}");
        // Pixel (410, 175) of 640x480 is canvas row 480 - 1 - 175.
        let (x, row, choices) = (410, 304, "{}");
        let json = |text: Option<String>| -> serde_json::Value {
            serde_json::from_str(&text.expect("an answer")).unwrap()
        };
        let reference = json(
            session
                .trace(x, row, 640, 480, choices, "course", "s.txt")
                .ok(),
        );
        assert_eq!(reference["y"], 175);
        let own = reference["text"].as_str().unwrap();
        let agrees = json(
            session
                .against(x, row, 640, 480, choices, "dbg.txt", own)
                .ok(),
        );
        assert_eq!(agrees["agrees"], true);
        assert!(agrees["text"].as_str().unwrap().contains("agrees"));
        // The README's example: a student's trace with the light's distance squared.
        let planted = include_str!("../../../examples/studio-410-175.dbg");
        let differs = json(
            session
                .against(x, row, 640, 480, choices, "dbg.txt", planted)
                .ok(),
        );
        assert_eq!(differs["agrees"], false);
        assert_eq!(differs["pixel"], serde_json::json!([410, 175]));
        let first = &differs["first_difference"];
        assert_eq!(first["quantity"], "distance to the light", "{first}");
        assert!(
            differs["text"]
                .as_str()
                .unwrap()
                .starts_with("first difference: ")
        );
    }
}
