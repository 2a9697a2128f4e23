//! The integration tests, linked into one binary (../shared/STYLE.md: one binary is cheaper to build
//! and link on a 2-core CI than one per file).

// `trace --against`: students' own debug traces, in every format of spec §8, with one
// planted mistake each.
mod against;
// The hard-case suite: the shipped kernel within 4 ulps, the textbook formula not.
mod accuracy;
// `compare --diagnose`'s causes: the mistakes of spec §7.5, alone and two together.
mod causes;
// The command line: sizes, formats, options, standard output holding only the image.
mod cli;
// `compare`: verdicts, reports, errors, and --diagnose naming every variant.
mod compare;
// Helpers: running the binary, listing scenes, snapshot settings.
mod common;
// The course's own scenes load; their dumps and images are snapshots.
mod course_scenes;
// Rays and shapes at the edge: tangents, axis-parallel rays, apexes.
mod degenerate;
// The docs name only code that exists, and their scene snippets load.
mod docs;
// The course notes' errors, each shown by a test.
mod errata;
// `grade`: a class made in the test; every row is compare's word on its pair.
mod grade;
// Every invalid input under tests/invalid/ gives a located error.
mod errors;
// Every example scene loads; its dump and image are snapshots.
mod examples;
// The hierarchy and the threads give the scan's and one thread's bytes.
mod performance;
// Pixel values derived from the formulas of spec §4.
mod pixels;
// `trace --against` on the real traces of ../shared/student-traces, edited and relabelled.
mod real_traces;
// What a hostile audit broke (issue 12): -o, pipes, limits, terminals.
mod reliability;
// Property tests: random, mutated and generated scenes load or fail cleanly, and render.
mod robustness;
// A scene scaled by 1e-3 and 1e3 keeps its image.
mod scale;
// The variants of spec §7.3: each rule's replacement, value by value.
mod variants;
// `trace` and the stages: trace bytes are image bytes; stage values from the formulas.
mod trace;
// Students' uploads: damaged, huge, non-regular, hard-linked, strangely named (issue 23).
mod untrusted;
