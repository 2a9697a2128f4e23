//! `legacy-rt [W] [H] < scene.txt > image.ppm`: the course's command, and `--dump`.

use super::interrupt;
use super::io::{emit_pieces_to_stdout, emit_to_stdout, read_scene};
use super::{Failure, RenderArgs, output_file, say, size};
use legacy_rt::image_output::file::OutputFile;
use legacy_rt::image_output::{self, Format};
use legacy_rt::render::{self, Show, object_colour};
use std::io::IsTerminal;

/// Renders the scene on standard input as `args` say, or dumps it.
pub fn run(args: &RenderArgs) -> Result<(), Failure> {
    let writing_to_terminal = args.output.is_none() && std::io::stdout().is_terminal();
    if writing_to_terminal && !args.dump {
        return Err(Failure::usage(
            "standard output is a terminal; redirect it to a file (> image.ppm) or use -o FILE",
        ));
    }
    let output = output_file(args.output.as_deref().filter(|_| !args.dump))?;
    args.how.check()?;
    let text = read_scene()?;
    // Read on the render's threads too: the same scene or error on any number.
    let scene = legacy_rt::scene::load_on(&text, &legacy_rt::scene::Disk, args.threads)
        .map_err(|error| Failure::load(None, error, 1))?;
    // The scene holds nothing of its text: free it before the render's own memory.
    drop(text);
    if args.dump {
        return emit_to_stdout(legacy_rt::dump(&scene).as_bytes());
    }
    let (width, height) = size((args.width, args.height), &scene)?;
    let options = legacy_rt::Options {
        threads: args.threads,
        ..args.how.options(&scene, width, height)?
    };
    legend(&scene, &options);
    let image = render_with_progress(&scene, &options);
    let format = output.as_ref().map_or(Format::Ppm, |o| o.format);
    write_image(&image, format, output)
}

/// The image, with a progress bar on standard error when it is a terminal.
pub fn render_with_progress(
    scene: &legacy_rt::Scene,
    options: &legacy_rt::Options,
) -> render::Image {
    let bar = std::io::stderr().is_terminal().then(|| {
        let bar = indicatif::ProgressBar::new(options.height as u64);
        bar.set_style(
            indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} rows, {eta} left")
                .expect("the template is valid"),
        );
        bar
    });
    let image = render::render(scene, options, |rows| {
        if let Some(bar) = &bar {
            bar.set_position(rows as u64);
        }
    });
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    image
}

/// Encodes the image and writes it to `output` or standard output.
pub fn write_image(
    image: &render::Image,
    format: Format,
    output: Option<OutputFile>,
) -> Result<(), Failure> {
    let encoded = image_output::encode(image, format)
        .map_err(|error| Failure::other(format!("cannot encode the image: {error}")))?;
    match output {
        Some(output) => output
            .write(&encoded.pieces(), interrupt::partial_file)
            .map_err(Failure::other),
        None => emit_pieces_to_stdout(&encoded.pieces()),
    }
}

/// What a diagnostic image's colours mean, on standard error: the objects' colours, or
/// the grey scale of the distances.
fn legend(scene: &legacy_rt::Scene, options: &legacy_rt::Options) {
    match options.show {
        Some(Show::Objects) => {
            say("legend: colour (r g b bytes) -> object");
            for (index, object) in scene.objects.iter().enumerate() {
                let [r, g, b] = object_colour(index).to_array().map(|c| (c * 255.0) as u8);
                say(&format!(
                    "  {r:3} {g:3} {b:3} -> {} (line {})",
                    object.kind(),
                    object.line
                ));
            }
            say("    0   0   0 -> nothing hit");
        }
        Some(Show::Depth) => say(&format!(
            "legend: grey = 255 x (1 - t / {}), t the distance from the eye to the first \
             hit (white near the eye, black at MAX_DIST and beyond, or nothing hit)",
            options.max_dist
        )),
        _ => {}
    }
}
