//! The record layouts of spec §3.2: for each type code, the groups that follow its line.
//!
//! The layout drives the reader: the format has no delimiters between groups other than
//! "N numbers, then the rest of the line is a comment" (spec §2.2), so the reader must
//! know N for every group before it reads it.

/// The labels of the groups. The meaning layer looks groups up by these names, and error
/// messages quote them ("the sphere's radius line").
pub mod label {
    /// The "world window" group.
    pub const WINDOW: &str = "world window";
    /// The "viewpoint" group.
    pub const VIEWPOINT: &str = "viewpoint";
    /// The "ambient" group.
    pub const AMBIENT: &str = "ambient";
    /// The "diffuse" group.
    pub const DIFFUSE: &str = "diffuse";
    /// The "specular" group.
    pub const SPECULAR: &str = "specular";
    /// The "background ambient" group.
    pub const BACK_AMBIENT: &str = "background ambient";
    /// The "background diffuse" group.
    pub const BACK_DIFFUSE: &str = "background diffuse";
    /// The "background specular" group.
    pub const BACK_SPECULAR: &str = "background specular";
    /// The "emissivity" group.
    pub const EMISSIVITY: &str = "emissivity";
    /// The "location" group.
    pub const LOCATION: &str = "location";
    /// The "aim point" group.
    pub const AIM: &str = "aim point";
    /// The "half-angle" group.
    pub const HALF_ANGLE: &str = "half-angle";
    /// The "centre" group.
    pub const CENTRE: &str = "centre";
    /// The "radius" group.
    pub const RADIUS: &str = "radius";
    /// The "normal" group.
    pub const NORMAL: &str = "normal";
    /// The "point" group.
    pub const POINT: &str = "point";
    /// The "x direction" group.
    pub const XDIR: &str = "x direction";
    /// The "size" group.
    pub const SIZE: &str = "size";
    /// The "tile size" group.
    pub const TILE_SIZE: &str = "tile size";
    /// The "texture file" group.
    pub const TEXTURE: &str = "texture file";
    /// The "mode" group.
    pub const MODE: &str = "mode";
    /// The "shader index" group.
    pub const SHADER: &str = "shader index";
    /// The "vertex" group.
    pub const VERTEX: &str = "vertex";
    /// The "base centre" group.
    pub const BASE: &str = "base centre";
    /// The "apex" group.
    pub const APEX: &str = "apex";
    /// The "waist centre" group.
    pub const WAIST_CENTRE: &str = "waist centre";
    /// The "centre line" group.
    pub const CENTRE_LINE: &str = "centre line";
    /// The "radius and height" group.
    pub const RADIUS_HEIGHT: &str = "radius and height";
    /// The "end radius and half-height" group.
    pub const END_RADIUS_HALF_HEIGHT: &str = "end radius and half-height";
    /// The "waist radius" group.
    pub const WAIST_RADIUS: &str = "waist radius";
    /// The ten numbers on the QUADRIC line (not a group of its own).
    pub const COEFFICIENTS: &str = "coefficients";
}

use label::*;

/// One group of a record: N numbers, or a file name token.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Slot {
    /// `count` numbers, then a comment to the end of the line.
    Numbers {
        /// The group's name.
        label: &'static str,
        /// How many numbers it holds.
        count: usize,
    },
    /// One whitespace-free token, then a comment (the textured plane's file name).
    FileName {
        /// The group's name.
        label: &'static str,
    },
}

impl Slot {
    /// The group's name.
    pub fn label(&self) -> &'static str {
        match self {
            Slot::Numbers { label, .. } | Slot::FileName { label } => label,
        }
    }
}

const fn n(label: &'static str, count: usize) -> Slot {
    assert!(count <= 3, "a group holds at most 3 numbers (GROUP_MAX)");
    Slot::Numbers { label, count }
}

/// The header: world window (2 numbers) and viewpoint (3), spec §2.1.
pub const HEADER: [Slot; 2] = [n(WINDOW, 2), n(VIEWPOINT, 3)];

/// A material block: ambient, diffuse and specular rgb (spec §3.1).
const M: [Slot; 3] = [n(AMBIENT, 3), n(DIFFUSE, 3), n(SPECULAR, 3)];

/// The layout of one record kind.
#[derive(Debug, PartialEq)]
pub struct Layout {
    /// The type code, or 0 for `QUADRIC`.
    pub code: u32,
    /// The record's name in messages ("sphere", "tiled plane").
    pub name: &'static str,
    /// The groups after the code line, in file order.
    pub slots: &'static [Slot],
}

macro_rules! layout {
    ($code:expr, $name:expr, [$($slot:expr),* $(,)?]) => {
        Layout { code: $code, name: $name, slots: &[$($slot),*] }
    };
}

/// Every supported type code, spec §3.2.
pub static LAYOUTS: [Layout; 13] = [
    layout!(10, "light", [n(EMISSIVITY, 3), n(LOCATION, 3)]),
    layout!(
        11,
        "spotlight",
        [
            n(EMISSIVITY, 3),
            n(LOCATION, 3),
            n(AIM, 3),
            n(HALF_ANGLE, 1)
        ]
    ),
    layout!(13, "sphere", [M[0], M[1], M[2], n(CENTRE, 3), n(RADIUS, 1)]),
    layout!(14, "plane", [M[0], M[1], M[2], n(NORMAL, 3), n(POINT, 3)]),
    layout!(
        15,
        "finite plane",
        [
            M[0],
            M[1],
            M[2],
            n(NORMAL, 3),
            n(POINT, 3),
            n(XDIR, 3),
            n(SIZE, 2)
        ]
    ),
    layout!(
        16,
        "tiled plane",
        [
            M[0],
            M[1],
            M[2],
            n(NORMAL, 3),
            n(POINT, 3),
            n(XDIR, 3),
            n(TILE_SIZE, 2),
            n(BACK_AMBIENT, 3),
            n(BACK_DIFFUSE, 3),
            n(BACK_SPECULAR, 3),
        ]
    ),
    layout!(
        17,
        "textured plane",
        [
            M[0],
            M[1],
            M[2],
            n(NORMAL, 3),
            n(POINT, 3),
            n(XDIR, 3),
            n(SIZE, 2),
            Slot::FileName { label: TEXTURE },
            n(MODE, 1),
        ]
    ),
    layout!(
        19,
        "procedural sphere",
        [M[0], M[1], M[2], n(CENTRE, 3), n(RADIUS, 1), n(SHADER, 1)]
    ),
    layout!(
        20,
        "procedural plane",
        [M[0], M[1], M[2], n(NORMAL, 3), n(POINT, 3), n(SHADER, 1)]
    ),
    layout!(
        21,
        "paraboloid",
        [
            M[0],
            M[1],
            M[2],
            n(VERTEX, 3),
            n(CENTRE_LINE, 3),
            n(RADIUS_HEIGHT, 2)
        ]
    ),
    layout!(
        22,
        "cylinder",
        [
            M[0],
            M[1],
            M[2],
            n(BASE, 3),
            n(CENTRE_LINE, 3),
            n(RADIUS_HEIGHT, 2)
        ]
    ),
    layout!(
        23,
        "cone",
        [
            M[0],
            M[1],
            M[2],
            n(APEX, 3),
            n(CENTRE_LINE, 3),
            n(RADIUS_HEIGHT, 2)
        ]
    ),
    layout!(
        24,
        "hyperboloid",
        [
            M[0],
            M[1],
            M[2],
            n(WAIST_CENTRE, 3),
            n(CENTRE_LINE, 3),
            n(END_RADIUS_HALF_HEIGHT, 2),
            n(WAIST_RADIUS, 1),
        ]
    ),
];

impl Layout {
    /// What the record holds, for error notes: "a sphere (type 13) has, one line each: ...".
    pub fn describe(&self) -> String {
        let slots: Vec<String> = self
            .slots
            .iter()
            .map(|slot| match slot {
                Slot::Numbers { label, count: 1 } => format!("{label} (1 number)"),
                Slot::Numbers { label, count } => format!("{label} ({count})"),
                Slot::FileName { label } => format!("{label} name"),
            })
            .collect();
        let head = match self.code {
            0 => format!("a {} (QUADRIC A B C D E F G H I J)", self.name),
            code => format!("a {} (type {code})", self.name),
        };
        format!("{head} has, one line each: {}", slots.join(", "))
    }
}

/// The `QUADRIC` record: its coefficients stand on the keyword's line; a material follows.
pub static QUADRIC: Layout = layout!(0, "quadric", [M[0], M[1], M[2]]);

/// Codes that other variants of the course used, with what they meant there and what to
/// tell the writer. The message must not suggest a renumbering: a file of another
/// variant also orders its lines differently, so a changed code loads nonsense silently.
pub fn unsupported(code: u32) -> Option<(&'static str, &'static str)> {
    match code {
        12 => Some((
            "projector",
            ": this file looks written for another version of the course, which numbered its \
             records differently and put their lines in another order, so changing the code \
             will not make it load; each record must be rewritten in this format, whose type \
             codes and lines are listed in docs/scene-format.md",
        )),
        18 => Some((
            "reflective sphere",
            ": the course never defined it; in this format every object reflects through its \
             specular line, so a mirror sphere is a sphere (type 13) with a non-zero specular \
             line (docs/scene-format.md)",
        )),
        _ => None,
    }
}

/// The layout of a type code, if the format defines it.
pub fn of_code(code: u32) -> Option<&'static Layout> {
    LAYOUTS.iter().find(|layout| layout.code == code)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_code_of_the_table_has_a_layout_and_no_other() {
        let defined: Vec<u32> = (0..100).filter(|&c| of_code(c).is_some()).collect();
        assert_eq!(
            defined,
            [10, 11, 13, 14, 15, 16, 17, 19, 20, 21, 22, 23, 24]
        );
    }

    #[test]
    fn labels_are_unique_within_a_record() {
        for layout in LAYOUTS.iter().chain([&QUADRIC]) {
            for (i, slot) in layout.slots.iter().enumerate() {
                assert!(
                    layout.slots[..i].iter().all(|s| s.label() != slot.label()),
                    "{} repeats {}",
                    layout.name,
                    slot.label()
                );
            }
        }
    }
}
