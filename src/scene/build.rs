//! Records to typed objects: each record kind's numbers go to its shape's constructor, and
//! a constructor's complaint is traced back to the number that caused it.

use super::{Beam, Light, Material, Object, Pattern, Scene, Shader, Texture, TextureMode};
use crate::error::{MeaningError, Pending};
use crate::scene_file::layout::label::*;
use crate::scene_file::{Group, GroupData, Record, SceneText};
use crate::shapes::{
    Cone, Cylinder, FinitePlane, Hyperboloid, Invalid, Paraboloid, Parameter, Plane, PlaneFrame,
    Quadric, Shape, Sphere, positive, unit,
};
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

pub(super) fn build(text: SceneText) -> Result<Scene, Pending> {
    let split = text.split.clone();
    build_scene(text).map_err(|error| match split {
        Some(split) => error.with_note(split),
        None => error,
    })
}

fn build_scene(text: SceneText) -> Result<Scene, Pending> {
    let window = pair(&text.window);
    let header_error = |index: usize| {
        let at = text.window.numbers()[index].at;
        move |error| Pending::new(at, error)
    };
    positive("world window", "width", window.x).map_err(header_error(0))?;
    positive("world window", "height", window.y).map_err(header_error(1))?;
    let mut scene = Scene {
        window,
        viewpoint: vec3(&text.viewpoint),
        lights: Vec::new(),
        objects: Vec::new(),
    };
    for record in &text.records {
        let located = |invalid| {
            let (name, line) = (record.layout.name, record.line);
            locate(record, invalid).with_note(format!("the {name} record starts on line {line}"))
        };
        match record.layout.code {
            10 | 11 => scene.lights.push(light(record).map_err(located)?),
            _ => scene.objects.push(object(record).map_err(located)?),
        }
    }
    Ok(scene)
}

/// The place of the number a constructor complained about.
fn locate(record: &Record, refusal: Refusal) -> Pending {
    let at = if refusal.label == COEFFICIENTS {
        record.coefficients[refusal.index].at
    } else {
        let group = record.group(refusal.label);
        group
            .numbers()
            .get(refusal.index)
            .map_or(group.at, |n| n.at)
    };
    Pending::new(at, refusal.error)
}

fn vec3(group: &Group) -> DVec3 {
    let n = group.numbers();
    DVec3::new(n[0].value, n[1].value, n[2].value)
}

fn pair(group: &Group) -> DVec2 {
    let n = group.numbers();
    DVec2::new(n[0].value, n[1].value)
}

fn scalar(group: &Group) -> f64 {
    group.numbers()[0].value
}

/// Normal, point and x direction of a framed plane (15, 16, 17).
fn frame_vectors(record: &Record) -> (DVec3, DVec3, DVec3) {
    let [normal, point, xdir] = [NORMAL, POINT, XDIR].map(|l| vec3(record.group(l)));
    (normal, point, xdir)
}

fn material(record: &Record, labels: [&str; 3]) -> Material {
    let [ambient, diffuse, specular] = labels.map(|l| vec3(record.group(l)));
    Material {
        ambient,
        diffuse,
        specular,
    }
}

fn light(record: &Record) -> Result<Light, Refusal> {
    let emissivity = vec3(record.group(EMISSIVITY));
    let location = vec3(record.group(LOCATION));
    let beam = if record.layout.code == 11 {
        let direction = unit(vec3(record.group(AIM)) - location).ok_or(Refusal {
            label: AIM,
            index: 0,
            error: MeaningError::AimAtLocation,
        })?;
        let half_angle = scalar(record.group(HALF_ANGLE));
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
    let value = scalar(record.group(SHADER));
    match value.trunc() {
        0.0 => Ok(Shader::Stripes),
        1.0 => Ok(Shader::ColourWheel),
        _ => Err(Refusal::of(SHADER, 0)(MeaningError::UnknownShader {
            record: record.layout.name,
            value,
        })),
    }
}

fn object(record: &Record) -> Result<Object, Refusal> {
    let name = record.layout.name;
    let group = |label| record.group(label);
    let mut pattern = Pattern::Plain;
    let refused = Refusal::of_shape(record.layout.code);
    let shape = match record.layout.code {
        13 | 19 => {
            let centre = vec3(group(CENTRE));
            let sphere = Sphere::new(centre, scalar(group(RADIUS)), name).map_err(&refused)?;
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
            let point = vec3(group(POINT));
            let plane = Plane::new(vec3(group(NORMAL)), point, name).map_err(&refused)?;
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
            let (normal, point, xdir) = frame_vectors(record);
            let plane =
                FinitePlane::new(normal, point, xdir, pair(group(SIZE)), name).map_err(&refused)?;
            if record.layout.code == 17 {
                pattern = texture(record, plane.size)?;
            }
            Shape::FinitePlane(plane)
        }
        16 => {
            let (normal, point, xdir) = frame_vectors(record);
            let frame = PlaneFrame::new(normal, point, xdir, name).map_err(&refused)?;
            let tile = pair(group(TILE_SIZE));
            positive(name, "tile width", tile.x).map_err(Refusal::of(TILE_SIZE, 0))?;
            positive(name, "tile height", tile.y).map_err(Refusal::of(TILE_SIZE, 1))?;
            let background = material(record, [BACK_AMBIENT, BACK_DIFFUSE, BACK_SPECULAR]);
            pattern = Pattern::Tiles { tile, background };
            Shape::TiledPlane(frame)
        }
        21..=24 => {
            let [r, h] = pair(group(if record.layout.code == 24 {
                END_RADIUS_HALF_HEIGHT
            } else {
                RADIUS_HEIGHT
            }))
            .to_array();
            let line = vec3(group(CENTRE_LINE));
            let first = |label| vec3(group(label));
            match record.layout.code {
                21 => {
                    Shape::Paraboloid(Paraboloid::new(first(VERTEX), line, r, h).map_err(&refused)?)
                }
                22 => Shape::Cylinder(Cylinder::new(first(BASE), line, r, h).map_err(&refused)?),
                23 => Shape::Cone(Cone::new(first(APEX), line, r, h).map_err(&refused)?),
                _ => {
                    let waist = scalar(group(WAIST_RADIUS));
                    Shape::Hyperboloid(
                        Hyperboloid::new(first(WAIST_CENTRE), line, r, h, waist)
                            .map_err(&refused)?,
                    )
                }
            }
        }
        _ => {
            let mut coefficients = [0.0; 10];
            for (c, number) in coefficients.iter_mut().zip(&record.coefficients) {
                *c = number.value;
            }
            Shape::Quadric(Quadric::new(coefficients).map_err(&refused)?)
        }
    };
    Ok(Object {
        shape,
        material: material(record, [AMBIENT, DIFFUSE, SPECULAR]),
        pattern,
        kind: name,
        line: record.line,
    })
}

/// The textured plane's texture and mode (spec §5.8), for a rectangle of `size`.
fn texture(record: &Record, size: DVec2) -> Result<Pattern, Refusal> {
    let mode_value = scalar(record.group(MODE));
    let mode = match mode_value.trunc() {
        1.0 => TextureMode::Fit,
        2.0 => TextureMode::Tile,
        _ => {
            let error = MeaningError::TextureMode { value: mode_value };
            return Err(Refusal::of(MODE, 0)(error));
        }
    };
    let GroupData::FileName(path) = &record.group(TEXTURE).data else {
        unreachable!("the texture slot holds a file name");
    };
    let texture = read_texture(path).map_err(|reason| {
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

/// Reads a binary P6 PPM, rows reordered bottom-up.
fn read_texture(path: &str) -> Result<Texture, String> {
    use image::ImageDecoder;
    use image::codecs::pnm::{PnmDecoder, PnmSubtype, SampleEncoding};
    // A FIFO or a device would block the load or never end; only a file is a texture.
    if !std::fs::metadata(path)
        .map_err(|e| e.to_string())?
        .is_file()
    {
        return Err("it is not a regular file".into());
    }
    let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    let mut decoder = PnmDecoder::new(std::io::BufReader::new(file)).map_err(|e| e.to_string())?;
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
    decoder.set_limits(limits).map_err(|e| e.to_string())?;
    let image = image::DynamicImage::from_decoder(decoder)
        .map_err(|e| e.to_string())?
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
