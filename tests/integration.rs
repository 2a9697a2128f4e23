//! The integration tests, linked into one binary (STYLE.md: one binary is cheaper to build
//! and link on a 2-core CI than one per file).

#[path = "integration/accuracy.rs"]
mod accuracy;
#[path = "integration/cli.rs"]
mod cli;
#[path = "integration/common.rs"]
mod common;
#[path = "integration/course_scenes.rs"]
mod course_scenes;
#[path = "integration/degenerate.rs"]
mod degenerate;
#[path = "integration/docs.rs"]
mod docs;
#[path = "integration/errata.rs"]
mod errata;
#[path = "integration/errors.rs"]
mod errors;
#[path = "integration/examples.rs"]
mod examples;
#[path = "integration/performance.rs"]
mod performance;
#[path = "integration/pixels.rs"]
mod pixels;
#[path = "integration/reliability.rs"]
mod reliability;
#[path = "integration/robustness.rs"]
mod robustness;
#[path = "integration/scale.rs"]
mod scale;
