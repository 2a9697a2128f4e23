//! Records to typed objects: each record kind's numbers go to its shape's constructor, and
//! a constructor's complaint is traced back to the number that caused it.

use super::{
    Beam, Files, Light, Look, Material, Object, Pattern, Scene, Shader, Texture, TextureMode,
};
use crate::error::{MeaningError, Pending};
use crate::scene_file::layout::label::*;
use crate::scene_file::{Group, GroupData, Record, Sink};
use crate::shapes::{
    Cone, Cylinder, FinitePlane, Hyperboloid, Invalid, Paraboloid, Parameter, Plane, PlaneFrame,
    Quadric, Shape, Sphere, positive, unit,
};
use crate::threads::Threads;
use glam::{DVec2, DVec3};
use std::sync::Arc;

/// The most texels a texture may have (a 16384 x 16384 image).
const MAX_TEXELS: u64 = 1 << 28;

/// A number of a record that describes no valid object: its group (by label), its index
/// in the group, and what is wrong.
struct Refusal {
    label: &'static str,
    index: usize,
    error: MeaningError,
}

impl Refusal {
    /// A refusal of number `index` of group `label`, for `map_err`.
    fn of(label: &'static str, index: usize) -> impl Fn(MeaningError) -> Refusal {
        move |error| Refusal {
            label,
            index,
            error,
        }
    }

    /// Where a shape's refused parameter stands in a record of type `code`.
    fn of_shape(code: u32) -> impl Fn(Invalid) -> Refusal {
        move |Invalid { parameter, error }| {
            let (label, index) = match (parameter, code) {
                (Parameter::Normal, _) => (NORMAL, 0),
                (Parameter::XDirection, _) => (XDIR, 0),
                (Parameter::CentreLine, _) => (CENTRE_LINE, 0),
                (Parameter::Radius, 13 | 19) => (RADIUS, 0),
                (Parameter::Radius, 24) => (END_RADIUS_HALF_HEIGHT, 0),
                (Parameter::Radius, _) => (RADIUS_HEIGHT, 0),
                (Parameter::Height, 15 | 17) => (SIZE, 1),
                (Parameter::Height, 24) => (END_RADIUS_HALF_HEIGHT, 1),
                (Parameter::Height, _) => (RADIUS_HEIGHT, 1),
                (Parameter::Width, _) => (SIZE, 0),
                (Parameter::Waist, _) => (WAIST_RADIUS, 0),
                (Parameter::Coefficients, _) => (COEFFICIENTS, 0),
            };
            Refusal {
                label,
                index,
                error,
            }
        }
    }
}

/// Builds the scene as the reader reads it ([`Sink`]): each record becomes a light or an
/// object at once, so the text's records are never all held. The first error in file
/// order is kept, and the reading goes on, because a syntax error anywhere in the file
/// is reported before it (as when the whole file was read first).
pub(super) struct Builder<'f> {
    scene: Scene,
    error: Option<Pending>,
    /// The line of the record with the error (0 for the header's).
    error_line: usize,
    files: &'f dyn Files,
}

impl<'f> Builder<'f> {
    /// A builder that reads texture files from `files`.
    pub(super) fn new(files: &'f dyn Files) -> Builder<'f> {
        let scene = Scene {
            window: DVec2::ZERO,
            viewpoint: DVec3::ZERO,
            lights: Vec::new(),
            objects: Vec::new(),
        };
        Builder {
            scene,
            error: None,
            error_line: 0,
            files,
        }
    }

    /// Room for `part`'s lights and objects, to come by [`adopt`](Self::adopt).
    pub(super) fn reserve_for(&mut self, part: &Builder<'_>) {
        self.scene.lights.reserve(part.scene.lights.len());
        self.scene.objects.reserve(part.scene.objects.len());
    }

    /// Whether an error was found: what comes after it is read, not built.
    pub(super) fn has_error(&self) -> bool {
        self.error.is_some()
    }

    /// Whether this builder, fed records read from a guess at a record's start
    /// (`src/scene/parallel.rs`), holds what its records from line `line` on give: it
    /// does unless it stopped building at an error before them.
    pub(super) fn holds_from(&self, line: usize) -> bool {
        self.error.is_none() || self.error_line >= line
    }

    /// Takes what `part`'s records from line `line` on give, as if this builder had
    /// been fed them after its own (which it [`holds_from`](Self::holds_from)): their
    /// lights and objects, the look of a run of equal plain materials shared across the
    /// seam, and their first error unless this builder has one already.
    pub(super) fn adopt(&mut self, part: Builder<'_>, line: usize, threads: &Threads) {
        if self.error.is_some() {
            return;
        }
        let Scene {
            lights,
            mut objects,
            ..
        } = part.scene;
        // Records start on lines of their own, in order: a record's light or object
        // comes from the line of its start, so the lines are increasing.
        let first = lights.partition_point(|light| light.line < line);
        self.scene.lights.extend(lights.into_iter().skip(first));
        let first = objects.partition_point(|object| object.line < line);
        if first > 0 {
            objects = objects.split_off(first);
        }
        if let (Some(last), Some(next)) = (self.scene.objects.last(), objects.first())
            && matches!(next.look.pattern, Pattern::Plain)
            && *last.look == *next.look
        {
            let (shared, theirs) = (Arc::clone(&last.look), Arc::clone(&next.look));
            for object in objects.iter_mut() {
                if !Arc::ptr_eq(&object.look, &theirs) {
                    break;
                }
                object.look = Arc::clone(&shared);
            }
        }
        // A million objects are moved on the threads.
        threads.append(&mut self.scene.objects, objects);
        if part.error.is_some() {
            self.error = part.error;
            self.error_line = part.error_line;
        }
    }

    /// The scene, or its first error with the reader's note on a group that ran across a
    /// line break (`split`), the likely cause of an error found after it.
    pub(super) fn finish(self, split: Option<String>) -> Result<Scene, Pending> {
        match (self.error, split) {
            (None, _) => Ok(self.scene),
            (Some(error), Some(split)) => Err(error.with_note(split)),
            (Some(error), None) => Err(error),
        }
    }

    fn keep(&mut self, result: Result<(), Pending>) {
        if let Err(error) = result {
            self.error = Some(error);
        }
    }
}

impl Sink for Builder<'_> {
    fn header(&mut self, window: Group, viewpoint: Group) {
        let result = header(&mut self.scene, &window, &viewpoint);
        self.keep(result);
    }

    fn record(&mut self, record: &Record) {
        if self.error.is_some() {
            return;
        }
        let located = |invalid| {
            let (name, line) = (record.layout.name, record.line);
            locate(record, invalid).with_note(format!("the {name} record starts on line {line}"))
        };
        self.error_line = record.line;
        let result = match record.layout.code {
            10 | 11 => light(record).map(|light| self.scene.lights.push(light)),
            _ => {
                let previous = self.scene.objects.last().map(|o| &o.look);
                let object = object(record, self.files, previous);
                object.map(|object| self.scene.objects.push(object))
            }
        };
        self.keep(result.map_err(located));
    }
}

/// The world window and the viewpoint, into `scene`.
fn header(scene: &mut Scene, window: &Group, viewpoint: &Group) -> Result<(), Pending> {
    // The reader reads the header's 2 and 3 numbers or fails; a shortfall here would be
    // this program's mistake, reported as one.
    let internal = |group: &Group| {
        let (at, label) = (group.at, group.label);
        move || {
            Pending::new(
                at,
                MeaningError::Internal {
                    record: "header",
                    label,
                },
            )
        }
    };
    let size = DVec2::from_array(window.values().ok_or_else(internal(window))?);
    let eye = viewpoint.values().ok_or_else(internal(viewpoint))?;
    let header_error = |index: usize| {
        let at = window.numbers().get(index).map_or(window.at, |n| n.at);
        move |error| Pending::new(at, error)
    };
    positive("world window", "width", size.x).map_err(header_error(0))?;
    positive("world window", "height", size.y).map_err(header_error(1))?;
    scene.window = size;
    scene.viewpoint = DVec3::from_array(eye);
    Ok(())
}

/// The place of the number a constructor complained about.
fn locate(record: &Record, refusal: Refusal) -> Pending {
    let numbers = if refusal.label == COEFFICIENTS {
        &record.coefficients[..]
    } else {
        record.group(refusal.label).map_or(&[][..], |g| g.numbers())
    };
    let group_at = record.group(refusal.label).map_or(record.at, |g| g.at);
    let at = numbers.get(refusal.index).map_or(group_at, |n| n.at);
    Pending::new(at, refusal.error)
}

/// The first `N` numbers of group `label` of `record`. The reader reads every group of the
/// record's layout, so a missing one is this program's mistake, reported as one.
fn values<const N: usize>(record: &Record, label: &'static str) -> Result<[f64; N], Refusal> {
    let values = record.group(label).and_then(Group::values::<N>);
    values.ok_or(Refusal {
        label,
        index: 0,
        error: MeaningError::Internal {
            record: record.layout.name,
            label,
        },
    })
}

fn vec3(record: &Record, label: &'static str) -> Result<DVec3, Refusal> {
    values::<3>(record, label).map(DVec3::from_array)
}

fn pair(record: &Record, label: &'static str) -> Result<DVec2, Refusal> {
    values::<2>(record, label).map(DVec2::from_array)
}

fn scalar(record: &Record, label: &'static str) -> Result<f64, Refusal> {
    values::<1>(record, label).map(|[value]| value)
}

/// Normal, point and x direction of a framed plane (15, 16, 17).
fn frame_vectors(record: &Record) -> Result<(DVec3, DVec3, DVec3), Refusal> {
    Ok((
        vec3(record, NORMAL)?,
        vec3(record, POINT)?,
        vec3(record, XDIR)?,
    ))
}

fn material(record: &Record, labels: [&'static str; 3]) -> Result<Material, Refusal> {
    let [ambient, diffuse, specular] = labels;
    Ok(Material {
        ambient: vec3(record, ambient)?,
        diffuse: vec3(record, diffuse)?,
        specular: vec3(record, specular)?,
    })
}

fn light(record: &Record) -> Result<Light, Refusal> {
    let emissivity = vec3(record, EMISSIVITY)?;
    let location = vec3(record, LOCATION)?;
    let beam = if record.layout.code == 11 {
        let direction = unit(vec3(record, AIM)? - location).ok_or(Refusal {
            label: AIM,
            index: 0,
            error: MeaningError::AimAtLocation,
        })?;
        let half_angle = scalar(record, HALF_ANGLE)?;
        if !(half_angle > 0.0 && half_angle < 180.0) {
            let error = MeaningError::SpotAngle { value: half_angle };
            return Err(Refusal::of(HALF_ANGLE, 0)(error));
        }
        Some(Beam {
            direction,
            half_angle,
            cos_limit: (half_angle * std::f64::consts::PI / 180.0).cos(),
        })
    } else {
        None
    };
    Ok(Light {
        emissivity,
        location,
        beam,
        line: record.line,
    })
}

/// A shader index, truncated to an integer (spec §5.5).
fn shader(record: &Record) -> Result<Shader, Refusal> {
    let value = scalar(record, SHADER)?;
    match value.trunc() {
        0.0 => Ok(Shader::Stripes),
        1.0 => Ok(Shader::ColourWheel),
        _ => Err(Refusal::of(SHADER, 0)(MeaningError::UnknownShader {
            record: record.layout.name,
            value,
        })),
    }
}

/// The object of `record`, sharing the look of the object before (`previous`) when the
/// two have the same plain material.
fn object(
    record: &Record,
    files: &dyn Files,
    previous: Option<&Arc<Look>>,
) -> Result<Object, Refusal> {
    let name = record.layout.name;
    let mut pattern = Pattern::Plain;
    let refused = Refusal::of_shape(record.layout.code);
    let shape = match record.layout.code {
        13 | 19 => {
            let centre = vec3(record, CENTRE)?;
            let sphere = Sphere::new(centre, scalar(record, RADIUS)?, name).map_err(&refused)?;
            if record.layout.code == 19 {
                let shader = shader(record)?;
                pattern = Pattern::Shader {
                    shader,
                    origin: centre,
                };
            }
            Shape::Sphere(sphere)
        }
        14 | 20 => {
            let point = vec3(record, POINT)?;
            let plane = Plane::new(vec3(record, NORMAL)?, point, name).map_err(&refused)?;
            if record.layout.code == 20 {
                let shader = shader(record)?;
                pattern = Pattern::Shader {
                    shader,
                    origin: point,
                };
            }
            Shape::Plane(plane)
        }
        15 | 17 => {
            let (normal, point, xdir) = frame_vectors(record)?;
            let plane = FinitePlane::new(normal, point, xdir, pair(record, SIZE)?, name)
                .map_err(&refused)?;
            if record.layout.code == 17 {
                pattern = texture(record, plane.size, files)?;
            }
            Shape::FinitePlane(Box::new(plane))
        }
        16 => {
            let (normal, point, xdir) = frame_vectors(record)?;
            let frame = PlaneFrame::new(normal, point, xdir, name).map_err(&refused)?;
            let tile = pair(record, TILE_SIZE)?;
            positive(name, "tile width", tile.x).map_err(Refusal::of(TILE_SIZE, 0))?;
            positive(name, "tile height", tile.y).map_err(Refusal::of(TILE_SIZE, 1))?;
            let background = material(record, [BACK_AMBIENT, BACK_DIFFUSE, BACK_SPECULAR])?;
            pattern = Pattern::Tiles {
                tile,
                background: Box::new(background),
            };
            Shape::TiledPlane(frame)
        }
        21..=24 => {
            let code = record.layout.code;
            let size = if code == 24 {
                END_RADIUS_HALF_HEIGHT
            } else {
                RADIUS_HEIGHT
            };
            let [r, h] = values::<2>(record, size)?;
            let line = vec3(record, CENTRE_LINE)?;
            let first = vec3(
                record,
                [VERTEX, BASE, APEX, WAIST_CENTRE][code as usize - 21],
            )?;
            match code {
                21 => Shape::Paraboloid(Box::new(
                    Paraboloid::new(first, line, r, h).map_err(&refused)?,
                )),
                22 => Shape::Cylinder(Box::new(
                    Cylinder::new(first, line, r, h).map_err(&refused)?,
                )),
                23 => Shape::Cone(Box::new(Cone::new(first, line, r, h).map_err(&refused)?)),
                _ => {
                    let waist = scalar(record, WAIST_RADIUS)?;
                    let shape = Hyperboloid::new(first, line, r, h, waist).map_err(&refused)?;
                    Shape::Hyperboloid(Box::new(shape))
                }
            }
        }
        _ => {
            let mut coefficients = [0.0; 10];
            for (c, number) in coefficients.iter_mut().zip(&record.coefficients) {
                *c = number.value;
            }
            Shape::Quadric(Box::new(Quadric::new(coefficients).map_err(&refused)?))
        }
    };
    let look = Look {
        material: material(record, [AMBIENT, DIFFUSE, SPECULAR])?,
        pattern,
    };
    let look = match previous {
        Some(shared) if matches!(look.pattern, Pattern::Plain) && **shared == look => {
            Arc::clone(shared)
        }
        _ => Arc::new(look),
    };
    Ok(Object {
        shape,
        look,
        line: record.line,
    })
}

/// The textured plane's texture and mode (spec §5.8), for a rectangle of `size`.
fn texture(record: &Record, size: DVec2, files: &dyn Files) -> Result<Pattern, Refusal> {
    let mode_value = scalar(record, MODE)?;
    let mode = match mode_value.trunc() {
        1.0 => TextureMode::Fit,
        2.0 => TextureMode::Tile,
        _ => {
            let error = MeaningError::TextureMode { value: mode_value };
            return Err(Refusal::of(MODE, 0)(error));
        }
    };
    let Some(GroupData::FileName(path)) = record.group(TEXTURE).map(|g| &g.data) else {
        let (record, label) = (record.layout.name, TEXTURE);
        return Err(Refusal::of(TEXTURE, 0)(MeaningError::Internal {
            record,
            label,
        }));
    };
    let texture = read_texture(path, files).map_err(|reason| {
        let error = MeaningError::Texture {
            path: path.clone(),
            reason,
        };
        Refusal::of(TEXTURE, 0)(error)
    })?;
    Ok(Pattern::Texture {
        texture: Arc::new(texture),
        mode,
        size,
    })
}

/// Reads a binary P6 PPM from `files`, rows reordered bottom-up.
fn read_texture(path: &str, files: &dyn Files) -> Result<Texture, String> {
    use image::ImageDecoder;
    use image::codecs::pnm::{PnmDecoder, PnmSubtype, SampleEncoding};
    use std::io::{BufRead, Read};
    // The file is whatever the scene names (any file of the machine running it): the
    // messages say what is wrong in words of their own, never quoting its bytes.
    let mut reader = files.open(path)?;
    let mut magic = [0u8; 2];
    let start = reader.fill_buf().map_err(|e| e.to_string())?;
    let seen = start.len().min(2);
    magic[..seen].copy_from_slice(&start[..seen]);
    if &magic != b"P6" {
        return Err("it is not a binary P6 PPM (its first bytes are not P6)".into());
    }
    let damaged = |error: image::ImageError| match error {
        image::ImageError::IoError(error) if error.kind() == std::io::ErrorKind::UnexpectedEof => {
            "it is cut short".to_string()
        }
        image::ImageError::Limits(_) => "it is larger than this program accepts".to_string(),
        _ => "its P6 header or texels are damaged".to_string(),
    };
    let mut decoder = PnmDecoder::new(reader.by_ref()).map_err(damaged)?;
    if decoder.subtype() != PnmSubtype::Pixmap(SampleEncoding::Binary) {
        return Err("it is not a binary P6 PPM".into());
    }
    let (width, height) = decoder.dimensions();
    if u64::from(width) * u64::from(height) > MAX_TEXELS {
        return Err(format!(
            "{width}x{height} texels is more than this program accepts"
        ));
    }
    let mut limits = image::Limits::default();
    limits.max_alloc = Some(MAX_TEXELS * 8);
    decoder.set_limits(limits).map_err(damaged)?;
    let image = image::DynamicImage::from_decoder(decoder)
        .map_err(damaged)?
        .into_rgb8();
    let (width, height) = (width as usize, height as usize);
    if width == 0 || height == 0 {
        return Err("it has no texels".into());
    }
    let texels = image
        .rows()
        .rev()
        .flat_map(|row| row.map(|p| p.0))
        .collect();
    Ok(Texture {
        path: path.to_string(),
        width,
        height,
        texels,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_group_the_layout_lacks_is_an_internal_error_not_a_panic() {
        // A sphere record read without its groups: asking for its centre reports the
        // builder's mistake with the record's place.
        let record = Record {
            layout: crate::scene_file::layout::of_code(13).unwrap(),
            at: 7,
            line: 3,
            coefficients: Vec::new(),
            groups: Vec::new(),
        };
        let refusal = vec3(&record, CENTRE).unwrap_err();
        let expected = MeaningError::Internal {
            record: "sphere",
            label: CENTRE,
        };
        assert_eq!(refusal.error, expected);
        assert_eq!(locate(&record, refusal).at, 7);
    }
}
