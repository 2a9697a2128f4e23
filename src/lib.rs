//! `legacy-rt`: an interpreter for the numeric scene files of a classic university
//! ray-tracing course.
//!
//! A scene flows text → records → typed scene → pixels → file:
//! `scene_file` reads the text into records (syntax only), [`scene`] validates them into
//! typed lights and [`shapes`], [`render`](mod@render) traces them as the course's C
//! program did, [`compare`] sets a student's image beside the reference, and
//! [`image_output`] writes PPM or PNG; `grade` grades a class's images (docs/architecture.md
//! has a paragraph per module).
//! The format and the rendering rules are those of the project's spec (`spec §N` in the
//! comments); the formulas are those of the course notes.
//!
//! ```
//! let text = "8 6  world\n0 0 3  viewpoint\n13 sphere\n1 1 1\n0 0 0\n0 0 0\n0 0 -3\n1\n";
//! let scene = legacy_rt::load(text).unwrap();
//! assert_eq!(scene.objects.len(), 1);
//! assert_eq!(scene.default_size(), (640, 480));
//! ```

#![warn(missing_docs)]

pub mod against;
pub mod compare;
pub mod error;
#[cfg(feature = "grade")]
pub mod files;
#[cfg(feature = "grade")]
pub mod grade;
pub mod image_output;
pub mod render;
pub mod scene;
pub(crate) mod scene_file;
pub mod shapes;
mod threads;

pub use error::SceneError;
pub use render::{Image, Options, render};
pub use scene::{Scene, dump, load, load_with};
