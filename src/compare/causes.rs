//! `compare --diagnose`'s causes: what the pixels support, in order, each with the count
//! of the differing pixels it explains and of the agreeing ones it would break.
//!
//! Whole-image causes come first, since they hide everything else: a square image's axes
//! swapped, every byte some levels off or the channels in another order (found from the
//! two images alone), then the catalogue's variants (a row or column off, the image
//! upside down, a scene rule: [`super::diagnose`]), and jittered camera rays (each
//! differing pixel against what the reference takes anywhere inside its pixel, or where
//! a candidate explains nearly all, what it leaves against the candidate's image). Each
//! cause found is undone and what remains is diagnosed again. A cause is stated only if
//! it explains at least half of the differing pixels left and breaks almost none
//! ([`supported`]); otherwise the report says no cause explains them.

use super::diagnose::{Diagnosis, Focus, SHIFTS, units, with_mask};
use super::flips::{Flip, flips};
use super::{Reference, differing, for_each_set, is_set, within};
use crate::render::variant::{Kind, Site};
use crate::render::{self, Image, Options, Variant};
use crate::scene::Scene;
use serde::Serialize;

/// A cause the pixels support.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Cause {
    /// What it is: the variants that render it, as `--variant` takes them
    /// (`row-offset=1`, `behind-root@12`), or `axes-swapped`, `bytes+3`, `channels=bgr`,
    /// `jitter`.
    pub id: String,
    /// The variants, where it is the catalogue's (in JSON their ids).
    pub variants: Vec<Variant>,
    /// What it does, in words.
    pub about: String,
    /// How many of the differing pixels it explains (of those the causes before it left).
    pub explains: usize,
    /// Of how many.
    pub of: usize,
    /// How many pixels that agreed it would make differ.
    pub breaks: usize,
    /// For a variant of one record: what it is, "cylinder (line 11)".
    #[serde(skip_serializing_if = "Option::is_none")]
    pub subject: Option<String>,
    /// A pixel it explains (x, y from the lower left, as `trace` takes them).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pixel: Option<[usize; 2]>,
    /// The whole-image causes that move the rays it was found under (in JSON their ids,
    /// as `--variant` takes them): those listed before it, or for a move and a scene
    /// mistake stated as one cause, its move. `pixel` is traced with them, so that the
    /// command traces the ray the student's pixel shows.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub under: Vec<Variant>,
    /// The command that traces `pixel` in the reference, when the command line knows the
    /// scene's file name.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub trace: Option<String>,
}

impl Cause {
    /// A cause found from the two images alone (no variant renders it).
    fn of_images(
        id: String,
        about: String,
        counts: [usize; 3],
        pixel: Option<[usize; 2]>,
    ) -> Cause {
        let [explains, of, breaks] = counts;
        Cause {
            id,
            variants: Vec::new(),
            about,
            explains,
            of,
            breaks,
            subject: None,
            pixel,
            under: Vec::new(),
            trace: None,
        }
    }

    /// A cause the catalogue's `variants` render, with what each does in words.
    fn of_variants(
        variants: &[Variant],
        [explains, of, breaks]: [usize; 3],
        subject: Option<String>,
        pixel: Option<[usize; 2]>,
    ) -> Cause {
        Cause {
            id: ids(variants),
            variants: variants.to_vec(),
            about: (variants.iter().map(|v| v.describe()))
                .collect::<Vec<_>>()
                .join("; "),
            explains,
            of,
            breaks,
            subject,
            pixel,
            under: Vec::new(),
            trace: None,
        }
    }

    /// Whether the cause lies only in how the image is written, the rays and their
    /// colours the reference's: rows, columns or axes moved, or the bytes' rule. A
    /// student's debug trace, ray by ray, then agrees with the reference.
    pub fn written_only(&self) -> bool {
        let written = |v: &Variant| SHIFTS.contains(&v.kind) || v.kind.row().site == Site::Bytes;
        match self.variants.is_empty() {
            // Found from the two images: all but jitter move or recode the bytes.
            true => self.id != JITTER,
            false => self.variants.iter().all(written),
        }
    }
}

/// The id of the cause that jittered camera rays are.
const JITTER: &str = "jitter";

/// A cause's share of what was left, at least: half.
pub(crate) const HALF: f64 = 0.5;

/// What a cause may break for each pixel it explains, at most: a twentieth.
pub(crate) const BREAKS_PER_FIX: usize = 20;

/// The fewest pixels jitter read in place may leave, where it explains nearly all, for
/// jitter about the pixels' centres to be read against it: fewer are jitter's own misses
/// (examples/spheres.txt jittered leaves 0 to 10).
const CENTRED_LEFT: usize = 10;

/// The least share of the differing pixels jitter read in place may leave, where it
/// explains nearly all, for jitter about the pixels' centres to be read against it: the
/// renderer's jitter about the centres leaves 1.6 % to 4.5 % on the examples and course
/// scenes at 160x120, its jitter alone 0.1 % to 0.7 % on the course scenes but spec1
/// (2 %).
const CENTRED_SHARE: f64 = 0.01;

/// A share of the differing pixels that leaves nothing to look for: the causes found
/// explain the image, and jitter is not looked for.
const NEARLY_ALL: f64 = 0.95;

/// Whether a cause that makes `explains` of `of` differing pixels agree and `breaks`
/// agreeing ones differ is one the pixels support.
pub fn supported(explains: usize, of: usize, breaks: usize) -> bool {
    explains > 0 && explains as f64 >= HALF * of as f64 && breaks * BREAKS_PER_FIX <= explains
}

/// What `compare --diagnose` finds: the candidates the catalogue's search found, where
/// the differences concentrate, the causes the pixels support, and the decisions on the
/// reference's paths whose change gives the student's bytes.
pub type Explained = (Vec<Diagnosis>, Option<Focus>, Vec<Cause>, Vec<Flip>);

/// The diagnosis of `student` against `rendered` (the scene's image under `options`):
/// the candidates the catalogue's search found, where the differences concentrate, the
/// causes the pixels support, and the decision flips of what the whole-image causes
/// leave ([`flips`]). `mask` says which pixels differ beyond
/// `levels`.
pub fn explain(
    scene: &Scene,
    options: &Options,
    rendered: &Reference,
    student: &Image,
    levels: u8,
    mask: (&[u64], usize),
) -> Explained {
    let reference = &rendered.image;
    let mut causes = Vec::new();
    if mask.1 == 0 {
        return (Vec::new(), None, causes, Vec::new());
    }
    // 1. The axes swapped and the bytes of the whole image: undone before anything else
    // is looked at.
    type Finder = fn(&Image, &Image, u8, (&[u64], usize)) -> Option<(Cause, Image)>;
    let mut student = std::borrow::Cow::Borrowed(student);
    let mut left: Option<(Vec<u64>, usize)> = None;
    for find in [swapped_cause as Finder, bytes_cause] {
        let now = left.as_ref().map_or(mask, |(m, n)| (&m[..], *n));
        if now.1 == 0 {
            break;
        }
        if let Some((cause, image)) = find(reference, &student, levels, now) {
            causes.push(cause);
            left = Some(differing(reference, &image, levels));
            student = std::borrow::Cow::Owned(image);
        }
    }
    let mask = left.as_ref().map_or(mask, |(m, n)| (&m[..], *n));
    if mask.1 == 0 {
        return (Vec::new(), None, causes, Vec::new());
    }
    let case = Case {
        scene,
        options,
        rendered,
        student: &student,
        levels,
    };
    let (found, mut focus, more) = scene_causes(case, mask);
    causes.extend(more);
    // Jitter is named once: the catalogue's seeded jitter, found in what the jitter read
    // from the pixels' footprints leaves, is that jitter confirmed, not a second cause
    // (d06 jittered and scaled by 256 was told jitter twice).
    let seeded =
        |c: &Cause| !c.variants.is_empty() && c.variants.iter().all(|v| v.kind == Kind::Jitter);
    if causes
        .iter()
        .any(|c| c.id == JITTER && c.variants.is_empty())
    {
        causes.retain(|c| !seeded(c));
    }
    let flips = decision_flips(case, mask, &causes);
    // One light's term or one object's colour is what is left where no decision differs.
    if let Some(focus) = focus.as_mut().filter(|_| !flips.is_empty()) {
        (focus.light, focus.material) = (None, None);
    }
    (found, focus, causes, flips)
}

/// What a diagnosis compares: the scene, the options its reference was rendered with,
/// the reference, the student's image (with whatever whole-image bytes were undone) and
/// the tolerance in levels.
#[derive(Clone, Copy)]
pub struct Case<'a> {
    /// The scene.
    pub scene: &'a Scene,
    /// The options of the reference.
    pub options: &'a Options,
    /// The reference, with its marks and paths.
    pub rendered: &'a Reference,
    /// The student's image.
    pub student: &'a Image,
    /// The tolerance, in byte levels.
    pub levels: u8,
}

/// The catalogue's causes of the differences `mask` of `student` left once the whole
/// image's bytes are undone (the scene's variants, jittered rays), with the candidates
/// found and where the differences concentrate.
fn scene_causes(case: Case, mask: (&[u64], usize)) -> SceneCauses {
    let Case {
        scene,
        options,
        rendered,
        student,
        levels,
    } = case;
    let reference = &rendered.image;
    let mut causes = Vec::new();
    // 2. The catalogue.
    let (found, focus) = with_mask(scene, options, rendered, student, levels, mask, (&[], &[]));
    let supported_causes = stated(&found, mask.1);
    let explained: usize = supported_causes.iter().map(|c| c.explains).sum();
    if explained as f64 >= NEARLY_ALL * mask.1 as f64 {
        // Jittered rays beside a mistake that changes far more pixels (an object hidden):
        // what the candidate leaves is read for jitter against the candidate's image.
        let left = mask.1.saturating_sub(explained);
        if left > 0
            && let Some(Through::Second([pair, jitter])) = jitter_through(case, mask, &found)
            && supported(jitter.explains, jitter.of, 0)
        {
            // A kernel stated beside (textbook: every ray rounded otherwise) that explains
            // half of the pixels jitter reads is their cause: read through the scene
            // variant alone, jitter takes the kernel's moves at edges for its own (the
            // tiny tracer's a02 without the division by the distance, whose sphere root
            // is the notes' formula: no-distance, textbook and jitter, 124 and 144 of the
            // 144 pixels the first leaves).
            let kernel = |c: &Cause| c.variants.iter().any(kernel);
            if (supported_causes.iter()).any(|c| kernel(c) && 2 * c.explains >= jitter.explains) {
                causes.extend(supported_causes);
                return (found, focus, causes);
            }
            if named(&supported_causes, &jitter.under) {
                // A kernel not among the candidates (a pair with a move: the search tries
                // no triple) may be what jitter reads: the kernel stated instead where
                // it explains half of jitter's pixels (the tiny tracer's a02 a row off
                // without the division by the distance: jitter was told on the 144
                // pixels of the sphere's edge the pair leaves, textbook explains 126).
                let kernel = kernel_beside(case, mask, &supported_causes)
                    .filter(|k| 2 * k.explains >= jitter.explains);
                causes.extend(supported_causes);
                causes.push(kernel.unwrap_or(jitter));
                return (found, focus, causes);
            }
            // Jitter read under a move that the causes stated do not name: a mistake that
            // changes nearly every pixel (a far clip that blacks out most of the image) in
            // an image a row off, where the move alone explains too few pixels to be
            // stated. Where jitter read under the move leaves under half of what it leaves
            // read in place, the move and the mistake are stated as one cause, then
            // jitter (d01 a row off, clipped at 10 and jittered was told the clip alone).
            let others: Vec<Variant> = (pair.variants.iter())
                .filter(|v| !SHIFTS.contains(&v.kind))
                .copied()
                .collect();
            let shown = (pair.subject.clone(), pair.pixel);
            let unmoved = jitter_through_image(case, mask, &others, shown);
            // What each reading leaves unexplained (jitter read first in place: nothing).
            let left_by = |first: &Cause, jitter: &Cause| {
                let read = supported(jitter.explains, jitter.of, 0);
                (first.of - first.explains).saturating_sub(if read { jitter.explains } else { 0 })
            };
            let unmoved_left = match &unmoved {
                Some(Through::Second([first, jitter])) => left_by(first, jitter),
                Some(Through::First(..)) => 0,
                None => left,
            };
            let moved_left = left_by(&pair, &jitter);
            if moved_left * 2 < unmoved_left && supported(pair.explains, pair.of, pair.breaks) {
                causes.extend([pair, jitter]);
                return (found, focus, causes);
            }
        }
        causes.extend(supported_causes);
        return (found, focus, causes);
    }
    // 3. Jittered rays: the pixels that lie within what the reference takes inside their
    // pixel are explained by them; what remains is diagnosed again.
    let own = |i: usize| Some(i);
    let in_place = jitter_cause(scene, options, reference, student, levels, mask, &own);
    // Jittered rays leave hardly a differing pixel outside what the reference takes
    // inside it; where they leave more, jitter stands only if another cause explains the
    // rest (an object moved by a pixel or two looks jittered on its shading).
    let clean =
        (in_place.as_ref()).is_some_and(|(c, ..)| c.explains as f64 >= NEARLY_ALL * c.of as f64);
    let in_place_left = (in_place.as_ref()).map(|(c, ..)| c.of - c.explains);
    // Jitter in place that is clean but leaves pixels where jitter read about the
    // pixels' centres leaves a quarter of them: rays jittered about the centres (the
    // renderer's on course scene a02 leave 135 of 6,725 in place, 2 about the centres;
    // jitter alone leaves 4 in place and 258 about the centres). Read only where in
    // place leaves at least a hundredth: jitter's own misses are fewer on the course
    // scenes, and the reading costs a render and the footprints again.
    let centred_left = |n: usize| n >= CENTRED_LEFT && n as f64 >= CENTRED_SHARE * mask.1 as f64;
    if clean
        && let Some(left_in_place) = in_place_left.filter(|&n| centred_left(n))
        && let Some(pair) = centred_pair(case, mask, |left| 4 * left <= left_in_place)
    {
        causes.extend(pair);
        return (found, focus, causes);
    }
    // 4. Where jitter in place is not found or leaves more, jittered rays also written a
    // row off (in place, a row off lies within the pixel's footprint on half its edges):
    // jitter read against the reference moved as the best move says.
    if !clean && let Some(pair) = moved_jitter(case, mask, &found) {
        causes.extend(pair);
        return (found, focus, causes);
    }
    if let Some((cause, repaired, off)) = in_place
        && let Some(after) = after_jitter(case, (cause, &repaired, off), clean)
    {
        // Jitter alone, leaving pixels that the best candidate of what it leaves explains
        // in part: jitter read again against that candidate's image, where a pixel the
        // second mistake changes is seen from elsewhere in the pixel (examples/spheres.txt
        // jittered without shadows: jitter explained 582 of 601, and no-shadows 7 of the
        // 18 left at the jittered tolerance).
        let alone = matches!(&after.2[..], [jitter] if jitter.explains < jitter.of);
        let through = || match jitter_through(case, mask, &after.0)? {
            Through::First(cause, repaired, off) => {
                after_jitter(case, (cause, &repaired, off), false)
            }
            Through::Second(_) => None,
        };
        if alone && let Some(through) = through().filter(|t| t.2.len() > 1) {
            causes.extend(through.2);
            return (through.0, through.1, causes);
        }
        causes.extend(after.2);
        return (after.0, after.1, causes);
    }
    // 5. Jittered rays with a second mistake that changes more pixels than jitter leaves
    // within the reference's footprints: jitter read against the image of the best
    // candidate, then the rest diagnosed again against the reference.
    match jitter_through(case, mask, &found) {
        Some(Through::First(cause, repaired, off)) => {
            if let Some(after) = after_jitter(case, (cause, &repaired, off), false) {
                causes.extend(after.2);
                return (after.0, after.1, causes);
            }
        }
        // Under a move, the pair's two causes as stated, each with its own counts and
        // pixel, where they are the pair's; then jitter, of what they leave.
        Some(Through::Second([first, jitter])) => {
            let mut stated: Vec<Variant> = (supported_causes.iter())
                .flat_map(|c| c.variants.clone())
                .collect();
            let mut pair = first.variants.clone();
            stated.sort_by_key(|v| v.id());
            pair.sort_by_key(|v| v.id());
            let explained: usize = supported_causes.iter().map(|c| c.explains).sum();
            let of = mask.1.saturating_sub(explained);
            if jitter.under.is_empty() || stated != pair {
                causes.extend([first, jitter]);
            } else if supported(jitter.explains.min(of), of, 0) {
                causes.extend(supported_causes);
                causes.push(Cause {
                    explains: jitter.explains.min(of),
                    of,
                    ..jitter
                });
            } else {
                causes.extend(supported_causes);
            }
            return (found, focus, causes);
        }
        None => {}
    }
    // 6. Jittered rays about the pixels' centres, where the catalogue found nothing to
    // read them through (examples/shadows.txt so was told nothing: its lit floor's
    // gradient leaves every sample past the reference's footprint on the image's left
    // and right, where the centre is nearly half a pixel away): stated where read about
    // the centres they leave under half of what they leave in place. Not again where
    // step 5 read them so and found no pair.
    let left_in_place = in_place_left.unwrap_or(mask.1);
    if !clean
        && supported_causes.is_empty()
        && !found.first().is_some_and(reads_centred)
        && let Some(pair) = centred_pair(case, mask, |left| 2 * left < left_in_place)
    {
        causes.extend(pair);
        return (found, focus, causes);
    }
    causes.extend(supported_causes);
    (found, focus, causes)
}

/// Whether `v`'s rule is a render option: a kernel (`textbook`, `textbook-f32`: every
/// ray's arithmetic otherwise, whose moves at edges read as jittered rays'), or
/// `max-dist`.
fn kernel(v: &Variant) -> bool {
    v.kind.row().site == Site::Option
}

/// The kernel (`textbook`, `textbook-f32`) that, beside the variants of `stated`,
/// explains the most of the differing pixels (`mask`) their image leaves, where the
/// pixels support it, counted as the search counts a pair's second: the differing pixels
/// the kernel's image beside them gives, less those their image gives, of those the
/// causes leave; and the agreeing pixels it makes differ, less those their image does.
fn kernel_beside(case: Case, (mask, count): (&[u64], usize), stated: &[Cause]) -> Option<Cause> {
    let (scene, options, student, levels) = (case.scene, case.options, case.student, case.levels);
    let variants: Vec<Variant> = stated.iter().flat_map(|c| c.variants.clone()).collect();
    let image = |variants: &[Variant]| -> Option<Image> {
        let options = options.with_variants(variants).ok()?;
        Some(render::render(scene, &options, |_| {}))
    };
    // The differing pixels an image gives, and the agreeing ones it makes differ.
    let counts = |image: &Image| {
        let pixels = image.pixels.iter().zip(&student.pixels).enumerate();
        pixels.fold((0usize, 0usize), |(fixed, broken), (i, (&a, &b))| {
            match (is_set(mask, i), within(a, b, levels)) {
                (true, true) => (fixed + 1, broken),
                (false, false) => (fixed, broken + 1),
                _ => (fixed, broken),
            }
        })
    };
    let theirs = image(&variants)?;
    let (fixed, broken) = counts(&theirs);
    // Of the pixels the causes stated leave, as they count them (a row off explains the
    // row it uncovers, whatever its pixels).
    let left = count.saturating_sub(stated.iter().map(|c| c.explains).sum());
    // Traced under the moves stated: the ray the student's pixel shows.
    let under: Vec<Variant> = (variants.iter())
        .filter(|v| SHIFTS.contains(&v.kind))
        .copied()
        .collect();
    let mut best: Option<Cause> = None;
    for kind in [Kind::Textbook, Kind::TextbookF32] {
        let kernel = Variant::of(kind);
        let Some(ours) = image(&[&variants[..], &[kernel]].concat()) else {
            continue;
        };
        let (both, both_broken) = counts(&ours);
        let explains = both.saturating_sub(fixed).min(left);
        let breaks = both_broken.saturating_sub(broken);
        let gives = |i: usize| {
            let own = |image: &Image| within(image.pixels[i], student.pixels[i], levels);
            is_set(mask, i) && own(&ours) && !own(&theirs)
        };
        if supported(explains, left, breaks) && best.as_ref().is_none_or(|b| explains > b.explains)
        {
            let pixel = (0..student.pixels.len())
                .find(|&i| gives(i))
                .map(|i| super::pixel_at(i, options.width, options.height));
            best = Some(Cause {
                under: under.clone(),
                ..Cause::of_variants(&[kernel], [explains, left, breaks], None, pixel)
            });
        }
    }
    best
}

/// Whether each of `moves` is among the variants of `causes`: jitter read under a move is
/// stated only with it.
fn named(causes: &[Cause], moves: &[Variant]) -> bool {
    (moves.iter()).all(|m| causes.iter().any(|c| c.variants.contains(m)))
}

/// What remains once jittered rays are undone (`repaired`: the student's image with the
/// pixels `cause` explains given the bytes of the image jitter was read against),
/// diagnosed again at the tolerance jitter leaves: the candidates, where they
/// concentrate, and the causes, jitter first; `None` where nothing is stated beside a
/// jitter that is not `clean` (that leaves more than a twentieth).
fn after_jitter(
    case: Case,
    (cause, repaired, off): (Cause, &Image, LevelOff),
    clean: bool,
) -> Option<SceneCauses> {
    let (rendered, student) = (case.rendered, case.student);
    let reference = &rendered.image;
    // Where what jitter leaves looks like a rule of the bytes, the rule beside it, read
    // at the student's own tolerance.
    if rule_suspected(&cause, off)
        && let Some(causes) = rule_beside_jitter(case, cause.of - cause.explains)
    {
        return Some((Vec::new(), None, causes));
    }
    // Under jittered rays a pixel a second mistake changes is that mistake's colour seen
    // from elsewhere in the pixel: on smooth shading, a few levels off.
    let levels = case.levels.max(JITTERED_LEVELS);
    let (mask, count) = differing(reference, repaired, levels);
    if count == 0 {
        return Some((Vec::new(), None, vec![cause]));
    }
    // The pixels jitter explains may lie on a second mistake's pixels too: they count
    // neither for nor against it.
    let mut explained = vec![0u64; mask.len()];
    for (i, (&r, &s)) in reference.pixels.iter().zip(&repaired.pixels).enumerate() {
        if r == s && student.pixels[i] != s {
            explained[i / 64] |= 1 << (i % 64);
        }
    }
    let mask = (&mask[..], count);
    let (scene, options) = (case.scene, case.options);
    // Jitter's pixels count neither way, and it stands for rays through the pixel's
    // corner, which are aimed inside it.
    let jitters = (&explained[..], &[Kind::PixelCentre][..]);
    let (found, focus) = with_mask(scene, options, rendered, repaired, levels, mask, jitters);
    // A rule of the bytes, which moves a byte by one level, is not read at the tolerance
    // jitter leaves: what it explains there is the jitter's (d01 a row off, jittered and
    // scaled by 256 was told round-bytes on 4,655 pixels). The seeded jitter found again
    // here stays, as support: [`explain`] names jitter once.
    let bytes = |c: &Cause| c.variants.iter().any(|v| v.kind.row().site == Site::Bytes);
    let rest: Vec<Cause> = (stated(&found, count).into_iter())
        .filter(|c| levels == case.levels || !bytes(c))
        .collect();
    (clean || !rest.is_empty()).then(|| {
        let causes = std::iter::once(cause).chain(rest).collect();
        (found, focus, causes)
    })
}

/// Whether what a reading of jitter (`cause`) left looks like a rule of the bytes beside
/// it: at least [`RULE_LEFT`] of the differing pixels, half of them at most a level above
/// what the reference takes inside the pixel and in no channel below it (`off`). A rule
/// raises a byte by one, past the footprint's colours where they are flat; what jittered
/// rays alone leave is a few pixels on edges and mirrors, where the footprint's samples
/// missed a colour, below it as often as above.
fn rule_suspected(cause: &Cause, off: LevelOff) -> bool {
    let left = cause.of.saturating_sub(cause.explains);
    left as f64 >= RULE_LEFT * cause.of as f64 && off.left > 0 && 2 * off.near >= off.left
}

/// The share of the differing pixels jittered rays, read in place, must leave for a rule
/// of the bytes beside them to be looked for ([`rule_suspected`]). Alone, they leave
/// 0.2 % to 0.35 % on the course scenes at 320x240 (d04 38 of 22,054 pixels, d06 112 of
/// 32,149), but spec1 1.3 % (416 of 32,362: its mirrors), of which 168 lie at most a
/// level above and none below, so that its rules are not read (counting a level below
/// too, 278 did, and they were read in vain); with a rule of the bytes, 3.6 % and more
/// (d04 scaled 841 of 23,227, 829 a level past; examples/shadows.txt at 160x120, 1.5 %),
/// nearly all of them above (spec1 rounded, 30,536 of 30,721; d06 scaled, 1,747 of 1,848).
const RULE_LEFT: f64 = 0.01;

/// Jittered rays and a rule of the bytes (d06 jittered and scaled by 256: jitter read
/// against the reference left 1,848 of 34,931 pixels, each a level or two off, which the
/// tolerance the diagnosis after jitter reads at cannot see): jitter read again against
/// the reference under each rule (its bytes stepped as its paths say, no ray traced but
/// the footprints'); where under one rule it leaves at most half the pixels it leaves
/// under the other, and the two explain nearly every differing pixel and break almost
/// none, jitter and that rule, with their counts against the reference: the one that
/// explains half first, jitter the differing pixels it reads within the footprints, the
/// rule those its image gives, and the agreeing pixels that neither gives as the rule's
/// breaks. The rule must also leave at most half of what jitter read in place left
/// (`left_in_place`): jittered rays alone leave pixels a level above the footprint's
/// samples where an edge cuts a gradient (examples/tiled_planes.txt jittered at 160x120:
/// 164 in place, 311 under scale-256, which was stated).
fn rule_beside_jitter(case: Case, left_in_place: usize) -> Option<Vec<Cause>> {
    let (rendered, student, levels) = (case.rendered, case.student, case.levels);
    let reference = &rendered.image;
    let pixels = reference.pixels.len();
    let own = |i: usize| Some(i);
    let under = |rule: Kind| {
        let (options, image) = under_rule(case, rule)?;
        let mask = differing(&image, student, levels);
        let (mask, count) = (&mask.0[..], mask.1);
        let (cause, repaired, _) = jitter_cause(
            case.scene,
            &options,
            &image,
            student,
            levels,
            (mask, count),
            &own,
        )?;
        Some((rule, image, repaired, count - cause.explains))
    };
    // The rule under which jitter leaves fewer pixels, where it leaves at most half as
    // many as under the other (examples/shadows.txt rounded: 23 pixels, 133 scaled).
    let [a, b] = [Kind::RoundBytes, Kind::Scale256].map(under);
    let leaves = |r: &Option<(Kind, Image, Image, usize)>| r.as_ref().map_or(usize::MAX, |r| r.3);
    let (best, other) = match leaves(&a) <= leaves(&b) {
        true => (a, leaves(&b)),
        false => (b, leaves(&a)),
    };
    let (rule, image, repaired, left) = best?;
    if left.saturating_mul(2) > other.min(left_in_place) {
        return None;
    }
    let (mask, count) = differing(reference, student, levels);
    let jittered = |i: usize| repaired.pixels[i] != student.pixels[i];
    let given = |i: usize| within(image.pixels[i], student.pixels[i], levels);
    // Which pixels each explains: jitter those it reads within the footprints, the rule
    // those its image gives; and the agreeing pixels neither gives, which the rule breaks.
    let [mut both, mut jitter_only, mut rule_only, mut breaks] = [0usize; 4];
    let [mut jitter_pixel, mut rule_pixel] = [None; 2];
    for i in 0..pixels {
        match (is_set(&mask, i), jittered(i), given(i)) {
            (true, true, true) => both += 1,
            (true, true, false) => {
                jitter_only += 1;
                jitter_pixel.get_or_insert(i);
            }
            (true, false, true) => {
                rule_only += 1;
                rule_pixel.get_or_insert(i);
            }
            (false, false, false) => breaks += 1,
            _ => {}
        }
    }
    if (((both + jitter_only + rule_only) as f64) < NEARLY_ALL * count as f64)
        || breaks * BREAKS_PER_FIX > both + rule_only
    {
        return None;
    }
    // The one that explains half first, with the pixels both explain; the other the rest
    // (at 640x480, d06's scaled bytes change more pixels than its jittered rays).
    let jitter_first = 2 * (both + jitter_only) >= count;
    let (jitter_explains, rule_explains) = match jitter_first {
        true => (both + jitter_only, rule_only),
        false => (jitter_only, both + rule_only),
    };
    let (jitter_of, rule_of) = match jitter_first {
        true => (count, count - jitter_explains),
        false => (count - rule_explains, count),
    };
    if !supported(rule_explains, rule_of, breaks) || !supported(jitter_explains, jitter_of, 0) {
        return None;
    }
    let (w, h) = (reference.width, reference.height);
    let at = |i: Option<usize>| i.map(|i| super::pixel_at(i, w, h));
    let jitter = Cause::of_images(
        JITTER.into(),
        "the camera rays look jittered, or aimed elsewhere inside their pixel: these \
                differing pixels lie within what the reference takes inside their pixel, \
                under the rule of the bytes named beside"
            .into(),
        [jitter_explains, jitter_of, 0],
        at(jitter_pixel),
    );
    let counts = [rule_explains, rule_of, breaks];
    let rule = Cause::of_variants(&[Variant::of(rule)], counts, None, at(rule_pixel));
    Some(match jitter_first {
        true => vec![jitter, rule],
        false => vec![rule, jitter],
    })
}

/// The options that render `rule` (round-bytes or scale-256) and the reference's image
/// under it, its bytes stepped as its paths say (no ray traced); `None` where the
/// reference was rendered without paths.
fn under_rule(case: Case, rule: Kind) -> Option<(Options, Image)> {
    let (rendered, reference) = (case.rendered, &case.rendered.image);
    if rendered.paths.len() != reference.pixels.len() {
        return None;
    }
    let options = case.options.with_variant(Variant::of(rule)).ok()?;
    let pixels = (rendered.paths.iter().zip(&reference.pixels))
        .map(|(&paths, &bytes)| paths.bytes(Some(rule), bytes))
        .collect();
    let image = Image {
        pixels,
        ..*reference
    };
    Some((options, image))
}

/// The candidates, where the differences concentrate, and the causes.
type SceneCauses = (Vec<Diagnosis>, Option<Focus>, Vec<Cause>);

/// What jittered rays read against a candidate's image give ([`jitter_through`]).
enum Through {
    /// Jitter, counted on the pixels it gives the reference's bytes, and the student's
    /// image with the pixels it explains given the candidate's, for the second mistake to
    /// be found in.
    First(Cause, Image, LevelOff),
    /// The candidate, then jitter: where jitter's own pixels are too few to state it
    /// first (the candidate changes nearly every pixel, as square-falloff does).
    Second([Cause; 2]),
}

/// Jittered rays read against the image of the best candidate of one scene variant
/// among `found` (no move: [`moved_jitter`] reads those), where a second mistake changes
/// so many pixels that jitter in place explains under half. Jitter is stated first where
/// it gives the reference's bytes to at least a twentieth of the differing pixels
/// (`mask`); else the candidate first, with the pixels its image gives, and jitter the
/// rest within what that image takes inside the pixel, where together they explain
/// nearly all and break almost nothing.
fn jitter_through(
    case: Case,
    (mask, count): (&[u64], usize),
    found: &[Diagnosis],
) -> Option<Through> {
    let best = found.first()?;
    // A scene variant paired with a kernel (textbook: every ray's rounding otherwise)
    // or with the pixel's centre reads as jitter's own pixels, which the kernel's and the
    // centre's moves at edges mimic: the scene variant alone is read first (d05 jittered
    // with its lights' falloff squared was told square-falloff with textbook, then
    // jitter; examples/spheres.txt jittered without the division by the distance,
    // no-distance alone, paired with pixel-centre).
    let edges = |v: &Variant| kernel(v) || v.kind == Kind::PixelCentre;
    if let [a, b] = best.variants[..]
        && edges(&a) != edges(&b)
    {
        let one = if edges(&a) { b } else { a };
        let alone = found.iter().find(|d| d.variants == [one]);
        let shown = alone.map_or((None, None), |d| (d.subject.clone(), d.pixel));
        if let Some(through) = jitter_through_image(case, (mask, count), &[one], shown) {
            return Some(through);
        }
    }
    // The centre paired with a kernel: the centre alone first, for the same reason (the
    // renderer's jitter about the centres on examples/studio.txt was told
    // pixel-centre,textbook-f32 and jitter).
    if let [_, _] = best.variants[..]
        && reads_centred(best)
        && let Some(through) = centred_jitter(case, (mask, count))
    {
        return Some(through);
    }
    let shown = (best.subject.clone(), best.pixel);
    jitter_through_image(case, (mask, count), &best.variants, shown)
}

/// Whether [`jitter_through`] reads jitter about the pixels' centres alone for `best`:
/// where it is the centre, or the centre with a kernel.
fn reads_centred(best: &Diagnosis) -> bool {
    let centre = Variant::of(Kind::PixelCentre);
    match best.variants[..] {
        [v] => v == centre,
        [a, b] => (a == centre && kernel(&b)) || (b == centre && kernel(&a)),
        _ => false,
    }
}

/// Jittered rays read about the pixels' centres (`pixel-centre`, spec §7.3): the pair,
/// where together they explain nearly every differing pixel.
fn centred_jitter(case: Case, mask: (&[u64], usize)) -> Option<Through> {
    let centre = Variant::of(Kind::PixelCentre);
    jitter_through_image(case, mask, &[centre], (None, None))
}

/// [`centred_jitter`]'s pair, where what it leaves unexplained passes `few`.
fn centred_pair(
    case: Case,
    mask: (&[u64], usize),
    few: impl Fn(usize) -> bool,
) -> Option<[Cause; 2]> {
    let Some(Through::Second(pair)) = centred_jitter(case, mask) else {
        return None;
    };
    let [first, jitter] = &pair;
    let left = (first.of - first.explains).saturating_sub(jitter.explains);
    few(left).then_some(pair)
}

/// [`jitter_through`] with the image of `variants`, shown by the subject and pixel of
/// `shown` where it is the candidate stated first.
fn jitter_through_image(
    case: Case,
    (mask, count): (&[u64], usize),
    variants: &[Variant],
    (subject, pixel): (Option<String>, Option<[usize; 2]>),
) -> Option<Through> {
    let (options, student, levels) = (case.options, case.student, case.levels);
    let reference = &case.rendered.image;
    // A move among them (a row off beside a scene mistake): jitter is read against the
    // image of the others, each student's pixel against the one the move brings there.
    let (moves, others): (Vec<Variant>, Vec<Variant>) =
        variants.iter().partition(|v| SHIFTS.contains(&v.kind));
    // Rays through the pixels' centres are read as a scene variant is: the footprints
    // are taken about their points. Any other camera rule is not read under jitter.
    let centred = others.iter().any(|v| v.kind == Kind::PixelCentre);
    if others.is_empty()
        || variants.iter().any(|v| {
            v.kind.row().site == Site::Camera && !moves.contains(v) && v.kind != Kind::PixelCentre
        })
    {
        return None;
    }
    let with = options.with_variants(&others).ok()?;
    let from: Box<dyn Fn(usize) -> Option<usize>> = match moves.is_empty() {
        true => Box::new(|i: usize| Some(i)),
        false => {
            let moved = options.with_variants(variants).ok()?;
            Box::new(super::diagnose::shifted_from(&with, &moved, &moves)?)
        }
    };
    let image = render::render(case.scene, &with, |_| {});
    let left = Moved::of(&image, case, mask, &from);
    let (cause, repaired, off) = jitter_cause(
        case.scene,
        &with,
        &image,
        student,
        levels,
        (&left.left, left.count),
        &from,
    )?;
    let differs = |i: usize| is_set(mask, i);
    let jittered = |i: usize| repaired.pixels[i] != student.pixels[i];
    let pixels = 0..reference.pixels.len();
    // Jitter's own pixels: those it gives back the reference's bytes. Under a move, which
    // is a cause of its own, jitter is never the first; nor about the centres, whose
    // image is the reference's wherever the centre moves a ray too little to matter.
    if moves.is_empty() && !centred {
        let explains = (pixels.clone())
            .filter(|&i| differs(i) && jittered(i) && repaired.pixels[i] == reference.pixels[i])
            .count();
        if explains as f64 >= (1.0 - NEARLY_ALL) * count as f64 {
            let cause = Cause {
                explains,
                of: count,
                ..cause
            };
            return Some(Through::First(cause, repaired, off));
        }
    }
    // The candidate's own pixels, those jitter explains of the rest, and the agreeing
    // pixels neither gives.
    let given =
        |i: usize| from(i).is_none_or(|j| within(image.pixels[j], student.pixels[i], levels));
    // Where the pixels the candidate leaves were too many to trace each (a 4096x4096
    // image), jitter's share of its sample stands for what it explains of the differing
    // and the agreeing ones among them.
    let all = left.count <= JITTER_REPAIR;
    let (fixed, mut rest, mut breaks) = pixels.fold((0, 0, 0), |(f, r, b), i| {
        match (differs(i), given(i), all && jittered(i)) {
            (true, true, _) => (f + 1, r, b),
            (true, false, true) => (f, r + 1, b),
            (false, false, false) => (f, r, b + 1),
            _ => (f, r, b),
        }
    });
    if !all {
        let share = |n: usize| cause.explains * n / left.count.max(1);
        let left_differing = count - fixed;
        rest = share(left_differing);
        breaks -= share(breaks);
    }
    let together = fixed + rest;
    if (together as f64) < NEARLY_ALL * count as f64 || breaks * BREAKS_PER_FIX > together {
        return None;
    }
    // A pixel the candidate's image gives, where the search named none.
    let pixel = pixel.or_else(|| {
        let (w, h) = (case.options.width, case.options.height);
        let i = (0..reference.pixels.len()).find(|&i| differs(i) && given(i))?;
        Some(super::pixel_at(i, w, h))
    });
    // The pair stated as one cause, a move and a scene mistake (a row off and a far
    // clip): its pixel is traced under the move, the ray the student's pixel shows.
    let first = Cause {
        under: moves.clone(),
        ..Cause::of_variants(variants, [fixed, count, breaks], subject, pixel)
    };
    let second = Cause {
        explains: rest,
        of: count - fixed,
        breaks: 0,
        under: moves,
        ..cause
    };
    Some(Through::Second([first, second]))
}

/// Jittered rays whose image is also moved (two of the real programs write every row one
/// row off, and one of them jitters its rays too): the best single move among the
/// catalogue's candidates `found`, and jitter read against the reference it moves, both
/// stated where together they explain nearly every differing pixel (`mask`) and break
/// almost nothing, with a third mistake where the two leave more ([`third_cause`]). The
/// move explains the pixels the moved reference gives (those past its edge too), jitter
/// those within what the moved reference takes inside the pixel;
/// the move breaks the agreeing pixels that neither explains. Neither alone explains
/// half: the move leaves every jittered pixel, and jitter read in place finds another
/// pixel's ray.
fn moved_jitter(
    case: Case,
    (mask, count): (&[u64], usize),
    found: &[Diagnosis],
) -> Option<Vec<Cause>> {
    let (options, student, levels) = (case.options, case.student, case.levels);
    let reference = &case.rendered.image;
    let (first, pixel) = found.iter().find_map(|d| match d.variants[..] {
        [v] if SHIFTS.contains(&v.kind) => Some((v, d.pixel)),
        _ => None,
    })?;
    let moved = options.with_variant(first).ok()?;
    let from = super::diagnose::shifted_from(options, &moved, &[first])?;
    let pixels = reference.pixels.len();
    let differs = |i: usize| is_set(mask, i);
    let agrees_moved =
        |i: usize| from(i).is_none_or(|j| within(reference.pixels[j], student.pixels[i], levels));
    // What the moved reference leaves differing, and how many pixels it fixes and breaks.
    let Moved {
        left,
        count: left_count,
        fixed,
        broken,
    } = Moved::of(reference, case, mask, &from);
    let left = (&left[..], left_count);
    let read = jitter_cause(case.scene, options, reference, student, levels, left, &from);
    // Where jitter cannot be read against the moved reference (a rule of the bytes moves
    // most of its bytes) or leaves what looks like a rule, the rule beside the two.
    let leaves = read.as_ref().map(|(c, ..)| left_count - c.explains);
    let suspected = match &read {
        Some((c, _, off)) => rule_suspected(c, *off),
        // Most of what the move leaves a level off (a rule moves every byte it changes
        // by one: 92 % and more of those pixels on the course scenes with a move, jitter
        // and a rule; with a mistake of the scene instead, 39 % at most).
        None => 2 * Moved::near(reference, case, left.0, &from) >= left_count,
    };
    if suspected
        && let Some(causes) = moved_rule_jitter(case, (mask, count), (first, pixel), &from, leaves)
    {
        return Some(causes);
    }
    let (jitter, repaired, _) = read?;
    // Whether jitter explains pixel i: it was given the moved reference's bytes.
    let repaired_at = |i: usize| student.pixels[i] != repaired.pixels[i];
    // Of what the move leaves, the differing pixels jitter explains and the agreeing ones
    // it does not: counted where every one was traced, else jitter's share of the sample.
    let (jittered, breaks) = match left_count <= JITTER_REPAIR {
        true => (0..pixels)
            .filter(|&i| is_set(left.0, i))
            .fold((0, 0), |(j, b), i| match (differs(i), repaired_at(i)) {
                (true, true) => (j + 1, b),
                (false, false) => (j, b + 1),
                _ => (j, b),
            }),
        false => {
            let share = |n: usize| jitter.explains * n / left_count.max(1);
            (share(left_count - broken), broken - share(broken))
        }
    };
    let explained = fixed + jittered;
    // A third mistake in what the two leave (the course program's cylinder, in a program
    // that also writes a row off and jitters its rays), where every pixel was traced.
    let third = match (explained as f64) < NEARLY_ALL * count as f64 && left_count <= JITTER_REPAIR
    {
        true => {
            let rest = (mask, count.saturating_sub(explained));
            third_cause(case, first, &repaired, rest, (&agrees_moved, &repaired_at))
        }
        false => None,
    };
    let explained = explained + third.as_ref().map_or(0, |c| c.explains);
    let breaks = breaks + third.as_ref().map_or(0, |c| c.breaks);
    // A rule of the bytes moves a byte by one level: at the tolerance jitter leaves,
    // round-bytes and scale-256 explain the same pixels to within a few (d01 a row off,
    // jittered and scaled by 256: 4,655 each of 4,696), and the catalogue's order among
    // them named the wrong one on 9 of 22 images. Its pixels count for the two; it is
    // not named.
    let third = third.filter(|c| c.variants.iter().all(|v| v.row().site != Site::Bytes));
    if (explained as f64) < NEARLY_ALL * count as f64 || breaks * BREAKS_PER_FIX > explained {
        return None;
    }
    let shift = Cause {
        id: ids(&[first]),
        variants: vec![first],
        about: first.describe(),
        explains: fixed,
        of: count,
        breaks,
        subject: None,
        pixel,
        under: Vec::new(),
        trace: None,
    };
    let jitter = Cause {
        explains: jittered,
        of: count - fixed,
        breaks: 0,
        under: vec![first],
        ..jitter
    };
    Some([shift, jitter].into_iter().chain(third).collect())
}

/// What an image moved as a move says (`from`: where each pixel of the student's image
/// comes from) leaves of the student's: the pixels it leaves differing, how many, and of
/// the differing pixels of `mask` how many it gives, of the agreeing how many it breaks.
struct Moved {
    left: Vec<u64>,
    count: usize,
    fixed: usize,
    broken: usize,
}

impl Moved {
    /// Of the pixels `left` marks, how many lie at most a level past `image` moved as
    /// `from` says, beyond the tolerance.
    fn near(
        image: &Image,
        case: Case,
        left: &[u64],
        from: &dyn Fn(usize) -> Option<usize>,
    ) -> usize {
        let (student, levels) = (case.student, case.levels);
        let mut near = 0;
        for_each_set(left, |i| {
            let Some(j) = from(i) else { return };
            let (a, b) = (image.pixels[j], student.pixels[i]);
            near += usize::from((0..3).all(|c| a[c].abs_diff(b[c]) <= levels.saturating_add(1)));
        });
        near
    }

    fn of(image: &Image, case: Case, mask: &[u64], from: &dyn Fn(usize) -> Option<usize>) -> Moved {
        let (student, levels) = (case.student, case.levels);
        let pixels = image.pixels.len();
        let agrees =
            |i: usize| from(i).is_none_or(|j| within(image.pixels[j], student.pixels[i], levels));
        let mut moved = Moved {
            left: vec![0u64; pixels.div_ceil(64)],
            count: 0,
            fixed: 0,
            broken: 0,
        };
        for i in 0..pixels {
            match (is_set(mask, i), agrees(i)) {
                (true, true) => moved.fixed += 1,
                (was, false) => {
                    moved.left[i / 64] |= 1 << (i % 64);
                    moved.count += 1;
                    moved.broken += usize::from(!was);
                }
                (false, true) => {}
            }
        }
        moved
    }
}

/// A move (`first`, with the pixel its candidate shows), jittered rays and a rule of the
/// bytes: a program that writes every row a row off, jitters its rays and rounds its
/// bytes (d06 so, at 320x240, was told the move and jitter, the rule's pixels counted for
/// them; with scale-256, whose bytes are most a level off, jitter could not be read and
/// d05 was told nothing). Jitter is read again against the moved reference under each
/// rule ([`under_rule`]); the rule under which it leaves at most half as many pixels as
/// under the other and as without a rule (`leaves`, `None` where it could not be read) is
/// stated with the move and jitter where the three explain nearly every differing pixel
/// of `mask` and break almost none. The move explains the differing pixels the moved
/// reference gives, the rule those its moved image gives besides, jitter those it reads
/// within the footprints of the rest (the larger of the two first, after the move); the
/// agreeing pixels none gives are the move's breaks.
fn moved_rule_jitter(
    case: Case,
    (mask, count): (&[u64], usize),
    (first, pixel): (Variant, Option<[usize; 2]>),
    from: &dyn Fn(usize) -> Option<usize>,
    leaves: Option<usize>,
) -> Option<Vec<Cause>> {
    let (student, levels) = (case.student, case.levels);
    let reference = &case.rendered.image;
    let under = |rule: Kind| {
        let (options, image) = under_rule(case, rule)?;
        let moved = Moved::of(&image, case, mask, from);
        let left = (&moved.left[..], moved.count);
        let (jitter, repaired, _) =
            jitter_cause(case.scene, &options, &image, student, levels, left, from)?;
        let leaves = moved.count - jitter.explains;
        Some((rule, image, moved, jitter, repaired, leaves))
    };
    let [a, b] = [Kind::RoundBytes, Kind::Scale256].map(under);
    let leaves_of = |r: &Option<(Kind, Image, Moved, Cause, Image, usize)>| {
        r.as_ref().map_or(usize::MAX, |r| r.5)
    };
    let (best, other) = match leaves_of(&a) <= leaves_of(&b) {
        true => (a, leaves_of(&b)),
        false => (b, leaves_of(&a)),
    };
    let (rule, image, moved, jitter, repaired, left) = best?;
    if left.saturating_mul(2) > other.min(leaves.unwrap_or(usize::MAX)) {
        return None;
    }
    let gives = |image: &Image, i: usize| {
        from(i).is_none_or(|j| within(image.pixels[j], student.pixels[i], levels))
    };
    let jittered = |i: usize| repaired.pixels[i] != student.pixels[i];
    // Where every pixel jitter left was traced, each is counted; else jitter's share of
    // its sample stands for what it explains of the differing and agreeing pixels left.
    let all = moved.count <= JITTER_REPAIR;
    let share = |n: usize| jitter.explains * n / moved.count.max(1);
    let [mut shift, mut ruled, mut jitters, mut breaks] = [0usize; 4];
    let [mut left_differing, mut left_agreeing] = [0usize; 2];
    let [mut rule_pixel, mut jitter_pixel] = [None; 2];
    for i in 0..reference.pixels.len() {
        let differs = is_set(mask, i);
        match (differs, gives(reference, i), gives(&image, i)) {
            (true, true, _) => shift += 1,
            (true, false, true) => {
                ruled += 1;
                rule_pixel.get_or_insert(i);
            }
            (_, _, true) => {}
            (_, _, false) if !all => match differs {
                true => left_differing += 1,
                false => left_agreeing += 1,
            },
            (true, _, false) if jittered(i) => {
                jitters += 1;
                jitter_pixel.get_or_insert(i);
            }
            (false, _, false) if !jittered(i) => breaks += 1,
            _ => {}
        }
    }
    if !all {
        jitters = share(left_differing);
        breaks = left_agreeing - share(left_agreeing);
    }
    let explained = shift + ruled + jitters;
    if (explained as f64) < NEARLY_ALL * count as f64 || breaks * BREAKS_PER_FIX > explained {
        return None;
    }
    let (w, h) = (reference.width, reference.height);
    let at = |i: Option<usize>| i.map(|i| super::pixel_at(i, w, h));
    let shift = Cause::of_variants(&[first], [shift, count, breaks], None, pixel);
    let rest = count - shift.explains;
    let rule = Cause {
        under: vec![first],
        ..Cause::of_variants(&[Variant::of(rule)], [ruled, rest, 0], None, at(rule_pixel))
    };
    let jitter = Cause {
        explains: jitters,
        of: rest,
        breaks: 0,
        pixel: if all { at(jitter_pixel) } else { jitter.pixel },
        under: vec![first],
        ..jitter
    };
    // The larger of the two after the move, the other of what it leaves.
    let (second, mut third) = match rule.explains >= jitter.explains {
        true => (rule, jitter),
        false => (jitter, rule),
    };
    third.of = rest - second.explains;
    (supported(second.explains, second.of, 0) && supported(third.explains, third.of, 0))
        .then(|| vec![shift, second, third])
}

/// A third cause, after a move (`first`) and jittered rays read against the reference it
/// moves: the catalogue's partner of the move in `repaired` (the student's image with the
/// pixels jitter explains given the moved reference's bytes, `jittered`), diagnosed at the
/// tolerance jitter leaves with those pixels counting neither way; counted on what the
/// two leave (the differing pixels of `mask` that neither explains, `rest` of them: not
/// within the moved reference, `agrees_moved`, and not jittered), against the image the
/// move and the partner render. Where the pixels support it.
fn third_cause(
    case: Case,
    first: Variant,
    repaired: &Image,
    (mask, rest): (&[u64], usize),
    (agrees_moved, jittered): (&dyn Fn(usize) -> bool, &dyn Fn(usize) -> bool),
) -> Option<Cause> {
    let (scene, options, student) = (case.scene, case.options, case.student);
    let reference = &case.rendered.image;
    let levels = case.levels.max(JITTERED_LEVELS);
    let (left, left_count) = differing(reference, repaired, levels);
    let pixels = reference.pixels.len();
    let mut ignored = vec![0u64; pixels.div_ceil(64)];
    for i in (0..pixels).filter(|&i| jittered(i)) {
        ignored[i / 64] |= 1 << (i % 64);
    }
    let (found, _) = with_mask(
        scene,
        options,
        case.rendered,
        repaired,
        levels,
        (&left, left_count),
        (&ignored, &[]),
    );
    // The move's partner, not a move itself.
    let second = found.iter().find_map(|d| match d.variants[..] {
        [a, b] if a == first && !SHIFTS.contains(&b.kind) => Some((b, d)),
        [a, b] if b == first && !SHIFTS.contains(&a.kind) => Some((a, d)),
        _ => None,
    });
    let (second, diagnosis) = second?;
    let both = options.with_variants(&[first, second]).ok()?;
    let image = render::render(scene, &both, |_| {});
    let given = |i: usize| within(image.pixels[i], student.pixels[i], levels);
    let (mut explains, mut breaks, mut pixel) = (0usize, 0usize, None);
    for i in (0..pixels).filter(|&i| !jittered(i)) {
        let left_by_two = is_set(mask, i) && !agrees_moved(i);
        match (left_by_two, given(i)) {
            (true, true) => {
                explains += 1;
                pixel = pixel.or(Some(i));
            }
            (false, false) if agrees_moved(i) => breaks += 1,
            _ => {}
        }
    }
    if !supported(explains, rest, breaks) {
        return None;
    }
    let (w, h) = (reference.width, reference.height);
    Some(Cause {
        id: ids(&[second]),
        variants: vec![second],
        about: second.describe(),
        explains,
        of: rest,
        breaks,
        subject: diagnosis.subject.clone().filter(|_| second.line.is_some()),
        pixel: pixel.map(|i| super::pixel_at(i, w, h)),
        under: vec![first],
        trace: None,
    })
}

/// The decision flips of the differences `mask` of `student` left by the whole-image
/// causes among `causes`: none under jittered rays (a pixel's bytes are then another
/// point's), and under a row or column offset, the image upside down or the like, those
/// of the reference moved as the cause says.
fn decision_flips(case: Case, mask: (&[u64], usize), causes: &[Cause]) -> Vec<Flip> {
    let options = case.options;
    if causes.iter().any(|c| c.id == JITTER) {
        return Vec::new();
    }
    let camera = (causes.iter().flat_map(|c| &c.variants)).filter(|v| v.row().site == Site::Camera);
    let moves: Vec<Variant> = camera.copied().collect();
    if moves.is_empty() {
        return flips(case, mask, &[]);
    }
    let Ok(moved) = options.with_variants(&moves) else {
        return Vec::new();
    };
    // The pixels that still differ from the reference moved so: where the moves only
    // shift the pixels, the reference's own bytes from where they come, and the
    // uncovered edge rendered; otherwise every differing pixel rendered.
    let from = super::diagnose::shifted_from(options, &moved, &moves);
    let (mut indices, mut rendered_at) = (Vec::with_capacity(mask.1), Vec::new());
    for_each_set(mask.0, |i| match from.as_ref().map(|from| from(i)) {
        Some(Some(j)) => indices.push((i, Some(j))),
        _ => {
            indices.push((i, None));
            rendered_at.push(i);
        }
    });
    let mut bytes = super::render_pixels(case.scene, &moved, &rendered_at).into_iter();
    let mut left = vec![0u64; mask.0.len()];
    let mut count = 0;
    for (i, from) in indices {
        let bytes = match from {
            Some(j) => Some(case.rendered.image.pixels[j]),
            None => bytes.next(),
        };
        if bytes.is_none_or(|b| !within(b, case.student.pixels[i], case.levels)) {
            left[i / 64] |= 1 << (i % 64);
            count += 1;
        }
    }
    let case = Case {
        options: &moved,
        ..case
    };
    flips(case, (&left, count), &moves)
}

/// The causes among the catalogue's best candidate (one variant, or a pair) that the
/// pixels support, of the `differing` pixels earlier causes left. One record hidden from
/// the camera and from the shadow rays, both stated, is one cause: the object missing.
fn stated(found: &[Diagnosis], differing: usize) -> Vec<Cause> {
    let mut causes = stated_apart(found, differing);
    if let [first, second] = &causes[..]
        && let both = [&first.variants[..], &second.variants[..]].concat()
        && missing_object(&both).is_some()
    {
        let counts = [
            first.explains + second.explains,
            first.of,
            first.breaks + second.breaks,
        ];
        let pixel = found.first().and_then(|d| d.pixel).or(first.pixel);
        let subject = first.subject.clone().or(second.subject.clone());
        causes = vec![Cause {
            about: missing_about(&both),
            ..Cause::of_variants(&both, counts, subject, pixel)
        }];
    }
    causes
}

/// The line of the record whose object `variants` leave out of every ray, where they
/// are `hidden@LINE` and `no-shadow@LINE` (in either order): the object missing, as a
/// reader that skipped its record or a list it was never added to draws it.
pub fn missing_object(variants: &[Variant]) -> Option<usize> {
    let [a, b] = variants else {
        return None;
    };
    let kinds = [a.kind, b.kind];
    let both = kinds.contains(&Kind::Hidden) && kinds.contains(&Kind::NoShadow);
    (both && a.line == b.line).then_some(a.line).flatten()
}

/// What the object missing does, in words.
fn missing_about(variants: &[Variant]) -> String {
    let line = missing_object(variants).map_or(String::new(), |l| format!(" on line {l}"));
    format!(
        "the object of the record{line} is missing: camera, mirror and shadow rays all pass \
         through it, instead of §4.6 and §4.3 every object is a candidate for every ray"
    )
}

/// [`stated`], each variant of a pair its own cause.
fn stated_apart(found: &[Diagnosis], differing: usize) -> Vec<Cause> {
    let Some(best) = found.first() else {
        return Vec::new();
    };
    let counts = |d: &Diagnosis| Some((d.explains?, d.breaks?));
    let found_alone = |variants: &[Variant]| found.iter().find(|d| d.variants == variants);
    // Which whole-image variants move the rays (a row off, the image upside down).
    let moving = |v: &[Variant]| v.iter().all(|v| v.kind.row().site == Site::Camera);
    // A cause, with the pixel that shows it: where it was rendered alone, its own, except
    // for the pair's partner, whose pixel is the pair's (one the first alone leaves); and
    // the partner listed after a first that moves the rays is traced under it.
    let best_units = units(&best.variants);
    let cause = |variants: &[Variant], (explains, of, breaks), before: &[Variant]| {
        let partner = best_units.len() == 2 && variants == best_units[1];
        let pixel = match partner {
            true => best.pixel,
            false => found_alone(variants).and_then(|d| d.pixel).or(best.pixel),
        };
        let under = match partner && before == best_units[0] && moving(before) {
            true => before.to_vec(),
            false => Vec::new(),
        };
        let subject = found_alone(variants).and_then(|d| d.subject.clone());
        Cause {
            under,
            ..Cause::of_variants(variants, [explains, of, breaks], subject, pixel)
        }
    };
    let alone = |variants: &[Variant]| found_alone(variants).and_then(counts);
    // The first cause: of a pair, a whole image's (the camera's or the bytes') before a
    // scene's, else the one that alone explains more.
    let whole = |v: &[Variant]| matches!(v[0].kind.row().site, Site::Camera | Site::Bytes);
    let explained_alone = |v: &[Variant]| alone(v).map_or(0, |(fixed, _)| fixed);
    let mut order = best_units.clone();
    order.sort_by_key(|&v| (!whole(v), std::cmp::Reverse(explained_alone(v))));
    let Some((fixed, broken)) = alone(order[0]) else {
        return Vec::new();
    };
    let first = cause(order[0], (fixed, differing, broken), &[]);
    let [_, second] = order[..] else {
        return match supported(fixed, differing, broken) {
            true => vec![first],
            false => Vec::new(),
        };
    };
    let Some((both, both_broken)) = counts(best) else {
        return Vec::new();
    };
    // A first that makes every differing pixel agree, and some agreeing ones differ, that
    // the pair leaves agreeing (an image upside down whose far clip blacks out pixels
    // that were black where they came from): what is left after it is what it breaks,
    // and the second makes all of those agree and breaks the ones the pair leaves.
    if fixed == differing && broken > 0 && both_broken == 0 {
        let repairs = (broken, broken, differing - both);
        if supported(repairs.0, repairs.1, repairs.2) {
            return vec![first, cause(second, repairs, order[0])];
        }
    }
    let (explains, of) = (both.saturating_sub(fixed), differing - fixed);
    let counts_second = (explains, of, both_broken.saturating_sub(broken));
    let second_cause = cause(second, counts_second, order[0]);
    let second_supported = supported(explains, of, second_cause.breaks);
    if supported(fixed, differing, broken) {
        return match second_supported {
            true => vec![first, second_cause],
            false => vec![first],
        };
    }
    // Two mistakes that each hide the other's pixels (a reader that stopped, in an image
    // a row off; a row off whose bytes are rounded): stated together where the pair is
    // supported and each explains at least half of what the other alone leaves, a move
    // before a rule of the bytes, else the one that explains more alone first.
    let Some((other, other_broken)) = alone(second) else {
        return Vec::new();
    };
    let each = |alone: usize| supported(both.saturating_sub(alone), differing - alone, both_broken);
    if !supported(both, differing, both_broken) || !each(fixed) || !each(other) {
        // Else the second alone, where the pixels support it: a partner that adds a few
        // pixels (round-bytes at a tolerance) hides no cause that explains nearly all.
        return match supported(other, differing, other_broken) {
            true => vec![cause(second, (other, differing, other_broken), &[])],
            false => Vec::new(),
        };
    }
    // A move of the rows or columns before a rule of the bytes (the rows are put back,
    // then the bytes are read); else the one that explains more alone first (the pixel's
    // centre, which alone makes few pixels agree, after the bytes' rule).
    let shift = |v: &[Variant]| SHIFTS.contains(&v[0].kind);
    let bytes = |v: &[Variant]| v[0].kind.row().site == Site::Bytes;
    let move_second = shift(second) && bytes(order[0]);
    let move_first = shift(order[0]) && bytes(second);
    let [(a, a_alone), (b, _)] = match move_second || (!move_first && other > fixed) {
        true => [(second, (other, other_broken)), (order[0], (fixed, broken))],
        false => [(order[0], (fixed, broken)), (second, (other, other_broken))],
    };
    vec![
        cause(a, (a_alone.0, differing, a_alone.1), &[]),
        cause(
            b,
            (
                both.saturating_sub(a_alone.0),
                differing - a_alone.0,
                both_broken.saturating_sub(a_alone.1),
            ),
            a,
        ),
    ]
}

/// Variants' ids joined by commas, as `--variant` takes them.
fn ids(variants: &[Variant]) -> String {
    variants
        .iter()
        .map(|v| v.id())
        .collect::<Vec<_>>()
        .join(",")
}

/// A square image's axes swapped (spec §7.5's x/y): the student's pixel at (x, y) is
/// the reference's at (y, x), as a program that swaps its loops' indices writes it, or
/// the file's rows and columns swapped (buf[x][y] for buf[y][x]). Checked on the
/// differing pixels first, given up once more than [`NEARLY_ALL`] allows miss; the
/// cause and the student's image with the axes swapped back.
fn swapped_cause(
    reference: &Image,
    student: &Image,
    levels: u8,
    (mask, count): (&[u64], usize),
) -> Option<(Cause, Image)> {
    let n = reference.width;
    if n != reference.height || n < 2 {
        return None;
    }
    // Where the student's file pixel i comes from in the reference's, either way.
    /// Pixel i of an n x n file to the reference's pixel it holds.
    type Source = fn(usize, usize) -> usize;
    let ways: [(&str, Source); 2] = [
        // (x, y) from (y, x): file row r, column c is x = c, y = n-1-r; the reference's
        // (n-1-r, c) is at row n-1-c, column n-1-r.
        ("x and y", |i, n| (n - 1 - i % n) * n + (n - 1 - i / n)),
        ("the file's rows and columns", |i, n| (i % n) * n + i / n),
    ];
    let may_miss = count - (NEARLY_ALL * count as f64).ceil() as usize;
    let differs = |i: usize| is_set(mask, i);
    for (what, from) in ways {
        let follows = |i: usize| within(reference.pixels[from(i, n)], student.pixels[i], levels);
        let mut missed = 0;
        let mut first = None;
        for i in (0..n * n).filter(|&i| differs(i)) {
            match follows(i) {
                true => first = first.or(Some(i)),
                false => missed += 1,
            }
            if missed > may_miss {
                break;
            }
        }
        if missed > may_miss {
            continue;
        }
        let explains = count - missed;
        let breaks = (0..n * n).filter(|&i| !differs(i) && !follows(i)).count();
        if !supported(explains, count, breaks) {
            continue;
        }
        let mut image = student.clone();
        for i in 0..n * n {
            image.pixels[from(i, n)] = student.pixels[i];
        }
        let cause = Cause::of_images(
            "axes-swapped".into(),
            format!("{what} are swapped: each pixel holds the one across the image's diagonal"),
            [explains, count, breaks],
            first.map(|i| super::pixel_at(i, n, n)),
        );
        return Some((cause, image));
    }
    None
}

/// The permutations of the channels other than RGB, by name, the most common mistake
/// first (BGR, as some image libraries store pixels): where an image cannot tell two
/// apart, the first is named.
const ORDERS: [(&str, [usize; 3]); 5] = [
    ("bgr", [2, 1, 0]),
    ("rbg", [0, 2, 1]),
    ("grb", [1, 0, 2]),
    ("gbr", [1, 2, 0]),
    ("brg", [2, 0, 1]),
];

/// Every byte shifted by one amount, or the channels in another order, over nearly all
/// the differing pixels (`mask`, and how many): the cause, and the student's image with it
/// undone. Each rule is first checked on the differing pixels, and given up as soon as
/// more of them than [`NEARLY_ALL`] allows do not follow it; only a rule that holds there
/// is counted on the agreeing pixels too.
fn bytes_cause(
    reference: &Image,
    student: &Image,
    levels: u8,
    (mask, count): (&[u64], usize),
) -> Option<(Cause, Image)> {
    let differing: Vec<usize> = {
        let mut all = Vec::with_capacity(count);
        for_each_set(mask, |i| all.push(i));
        all
    };
    let pair = |i: usize| (reference.pixels[i], student.pixels[i]);
    let may_miss = count - (NEARLY_ALL * count as f64).ceil() as usize;
    // How many differing pixels `follows` holds on, or None once too many miss.
    let explained = |follows: &dyn Fn([u8; 3], [u8; 3]) -> bool| {
        let mut missed = 0;
        for &i in &differing {
            let (r, s) = pair(i);
            if !follows(r, s) {
                missed += 1;
                if missed > may_miss {
                    return None;
                }
            }
        }
        Some(count - missed)
    };
    // The agreeing pixels `follows` would make differ.
    let breaks = |follows: &dyn Fn([u8; 3], [u8; 3]) -> bool| {
        let pairs = reference.pixels.iter().zip(&student.pixels);
        (pairs.enumerate())
            .filter(|&(i, (&r, &s))| !is_set(mask, i) && !follows(r, s))
            .count()
    };
    // The first differing pixel `follows` explains, as `trace` takes it.
    let first = |follows: &dyn Fn([u8; 3], [u8; 3]) -> bool| {
        let i = differing.iter().find(|&&i| follows(pair(i).0, pair(i).1))?;
        Some(super::pixel_at(*i, reference.width, reference.height))
    };
    let undone = |follows: &dyn Fn([u8; 3], [u8; 3]) -> bool| {
        let mut image = student.clone();
        for &i in &differing {
            let (r, s) = pair(i);
            if follows(r, s) {
                image.pixels[i] = r;
            }
        }
        image
    };
    // A shift: the student's byte is the reference's plus d, clamped to 0-255; d is read
    // from the channel that moved most (one clamped at 0 or 255 moved less).
    let shifted = |r: [u8; 3], d: i32| r.map(|c| (i32::from(c) + d).clamp(0, 255) as u8);
    let mut tally = [0usize; 511];
    for &i in &differing {
        let (r, s) = pair(i);
        let d = (0..3)
            .map(|c| i32::from(s[c]) - i32::from(r[c]))
            .max_by_key(|d| d.abs())
            .unwrap_or(0);
        if d != 0 && shifted(r, d) == s {
            tally[(d + 255) as usize] += 1;
        }
    }
    let (at, &most) = (tally.iter().enumerate()).max_by_key(|&(i, n)| (n, std::cmp::Reverse(i)))?;
    let d = at as i32 - 255;
    let shift = move |r: [u8; 3], s: [u8; 3]| within(shifted(r, d), s, levels);
    if most + may_miss >= count {
        let broken = breaks(&shift);
        if supported(most, count, broken) {
            let cause = Cause::of_images(
                format!("bytes{d:+}"),
                format!(
                    "every byte is {} level{} {} the reference's; compare --tolerance {} passes such an image",
                    d.abs(),
                    if d.abs() == 1 { "" } else { "s" },
                    if d > 0 { "above" } else { "below" },
                    d.abs()
                ),
                [most, count, broken],
                first(&shift),
            );
            return Some((cause, undone(&shift)));
        }
    }
    for (name, order) in ORDERS {
        let swapped = move |r: [u8; 3], s: [u8; 3]| within(order.map(|k| r[k]), s, levels);
        let Some(explains) = explained(&swapped) else {
            continue;
        };
        let broken = breaks(&swapped);
        if !supported(explains, count, broken) {
            continue;
        }
        let cause = Cause::of_images(
            format!("channels={name}"),
            format!("the channels are written in the order {name}, not rgb"),
            [explains, count, broken],
            first(&swapped),
        );
        return Some((cause, undone(&swapped)));
    }
    None
}

/// The most differing pixels the jitter check looks at: beyond it, every n-th.
const JITTER_PIXELS: usize = 20_000;

/// Of the pixels where the reference varies inside the pixel, the share that jittered
/// rays change at least: measured at 320x240, from 21 % on the flat colours of course
/// scene a02 to 86 % on examples/cones.txt's shading, where a sphere moved by two pixels
/// changes 4-13 % (examples/shadows.txt, mirrors.txt, spec1.txt).
const SPREAD: f64 = 0.15;

/// How many pixels of the whole image the jitter check samples for its spread.
const SPREAD_PIXELS: usize = 4096;

/// The tolerance the causes after jitter are looked for at: what moving a ray inside
/// its pixel changes on smooth shading.
const JITTERED_LEVELS: u8 = 3;

/// The most differing pixels jitter is undone on, each traced: beyond it, the sample's.
const JITTER_REPAIR: usize = 200_000;

/// Where in a pixel the jitter check samples the reference, in pixels from its centre:
/// the centre, the corners, the edges' middles.
const SUB_PIXEL: [(f64, f64); 9] = [
    (0.0, 0.0),
    (-0.5, -0.5),
    (0.5, 0.5),
    (-0.5, 0.5),
    (0.5, -0.5),
    (0.0, -0.5),
    (0.0, 0.5),
    (-0.5, 0.0),
    (0.5, 0.0),
];

/// The stride of the jitter check's sample of the whole image (`w` by `h`), about
/// [`SPREAD_PIXELS`] pixels: the least at or above (w·h)/SPREAD_PIXELS that shares no
/// factor with the width. A stride the width divides (4096 at 4096x4096) would sample one
/// column, and one that shares a factor with it, a few.
fn spread_stride(w: usize, h: usize) -> usize {
    let gcd = |mut a: usize, mut b: usize| {
        while b != 0 {
            (a, b) = (b, a % b);
        }
        a
    };
    let mut spread = (w * h).div_ceil(SPREAD_PIXELS).max(1);
    while gcd(spread, w) != 1 {
        spread += 1;
    }
    spread
}

/// Whether the camera rays look jittered: at least half the differing pixels lie within
/// what the reference takes anywhere inside their pixel (its value at the pixel's
/// corners, edges and centre, per channel, within the tolerance), and a good share of the
/// pixels where the reference varies inside the pixel differ, all over the image
/// ([`SPREAD`]: a moved object changes pixels within its reach only). The cause, and the student's
/// image with those pixels the reference's.
fn jitter_cause(
    scene: &Scene,
    options: &Options,
    reference: &Image,
    student: &Image,
    levels: u8,
    (mask, count): (&[u64], usize),
    from: &dyn Fn(usize) -> Option<usize>,
) -> Option<(Cause, Image, LevelOff)> {
    let (w, h) = (options.width, options.height);
    let every = count.div_ceil(JITTER_PIXELS).max(1);
    let differs = |i: usize| is_set(mask, i);
    let differing_pixels = || (0..w * h).filter(|&i| differs(i));
    let looked: Vec<usize> = differing_pixels().step_by(every).collect();
    render::tracing(scene, options, |frame| {
        let origin = frame.world(0, 0);
        let step = glam::DVec3::new(
            frame.world(1.min(w - 1), 0).x - origin.x,
            frame.world(0, 1.min(h - 1)).y - origin.y,
            0.0,
        );
        // The reference's bytes at the centre, corners and edges' middles of the pixel
        // whose ray the student's pixel i shows (its own, or where a move brings it from),
        // in turn. The centre's are the reference's pixel; a corner is shared by four
        // pixels and an edge's middle by two, so each point of the half-pixel lattice is
        // traced once, from the first pixel that asks for it (in a fixed order: the same
        // bytes on every run).
        let traced = std::cell::RefCell::new(rustc_hash::FxHashMap::default());
        let samples = |i: usize| {
            let j = from(i).unwrap_or(i);
            let (x, y) = (j % w, options.row_of(j / w));
            let centre = frame.world(x, y);
            let traced = &traced;
            SUB_PIXEL.iter().map(move |&(dx, dy)| {
                if (dx, dy) == (0.0, 0.0) {
                    // The render's camera ray through the pixel is this one: the same bytes.
                    debug_assert_eq!(reference.pixels[j], frame.bytes_through(centre));
                    return reference.pixels[j];
                }
                // The lattice point: 2x + 1 + 2dx across, 2y + 1 + 2dy up.
                let at = |p: usize, d: f64| (2 * p + 1).wrapping_add_signed((2.0 * d) as isize);
                let key = (at(x, dx), at(y, dy));
                *(traced.borrow_mut().entry(key)).or_insert_with(|| {
                    let offset = glam::DVec3::new(dx * step.x, dy * step.y, 0.0);
                    frame.bytes_through(centre + offset)
                })
            })
        };
        // Of the pixels read and left, those at most a level above what the reference
        // takes inside the pixel and in no channel below, and how many were left.
        let level_off = std::cell::Cell::new(LevelOff::default());
        // Whether the student's pixel i lies within what the reference takes inside the
        // pixel, per channel, within the tolerance: the samples stop once it does.
        let consistent = |i: usize| {
            let s = student.pixels[i];
            let (mut low, mut high) = ([255u8; 3], [0u8; 3]);
            let within = samples(i).any(|bytes| {
                for c in 0..3 {
                    low[c] = low[c].min(bytes[c]);
                    high[c] = high[c].max(bytes[c]);
                }
                (0..3).all(|c| {
                    s[c].saturating_add(levels) >= low[c] && s[c] <= high[c].saturating_add(levels)
                })
            });
            if !within {
                // A rule of the bytes (round-bytes, scale-256) gives a byte at or above the
                // truncation's, at most a level above: a pixel below the footprint's
                // colours in any channel is no rule's.
                let below = (0..3).any(|c| s[c].saturating_add(levels) < low[c]);
                let above = (0..3)
                    .map(|c| s[c].saturating_sub(high[c].saturating_add(levels)))
                    .max()
                    .unwrap_or(0);
                let LevelOff { near, left } = level_off.get();
                level_off.set(LevelOff {
                    near: near + usize::from(!below && above <= 1),
                    left: left + 1,
                });
            }
            within
        };
        // Whether the reference varies by more than the tolerance inside pixel i.
        let varies = |i: usize| {
            let (mut low, mut high) = ([255u8; 3], [0u8; 3]);
            samples(i).any(|bytes| {
                for c in 0..3 {
                    low[c] = low[c].min(bytes[c]);
                    high[c] = high[c].max(bytes[c]);
                }
                (0..3).any(|c| high[c] - low[c] > levels.saturating_add(1))
            })
        };
        let verdicts: Vec<bool> = looked.iter().map(|&i| consistent(i)).collect();
        let agreeing = verdicts.iter().filter(|&&v| v).count();
        if (agreeing as f64) < HALF * looked.len() as f64 || agreeing == 0 {
            return None;
        }
        // Jittered rays change the pixels wherever the reference varies inside a pixel, all
        // over the image; a moved object changes them only within its reach. Of the pixels
        // where the reference varies (a sample of the whole image), [`SPREAD`] differ.
        let spread = spread_stride(w, h);
        let (mut varying, mut changed) = (0usize, 0usize);
        let shown = |i: usize| from(i).is_some();
        for i in (0..w * h)
            .step_by(spread)
            .filter(|&i| shown(i) && varies(i))
        {
            varying += 1;
            changed += usize::from(differs(i));
        }
        if (changed as f64) < SPREAD * varying as f64 {
            return None;
        }
        // Undone on every differing pixel it explains (a sample where they are too many to
        // trace), so that what remains is the rest of the student's mistakes.
        let all = count <= JITTER_REPAIR;
        // The k-th differing pixel was looked at already where k is a multiple of `every`.
        let looked_at = |k: usize| k.is_multiple_of(every).then(|| verdicts[k / every]);
        let repair: Vec<usize> = match all {
            true => (differing_pixels().enumerate())
                .filter(|&(k, i)| looked_at(k).unwrap_or_else(|| consistent(i)))
                .map(|(_, i)| i)
                .collect(),
            false => (looked.iter().zip(&verdicts))
                .filter(|&(_, &v)| v)
                .map(|(&i, _)| i)
                .collect(),
        };
        let mut repaired = student.clone();
        for &i in &repair {
            repaired.pixels[i] = reference.pixels[from(i).unwrap_or(i)];
        }
        let explains = match all {
            true => repair.len(),
            false => (agreeing as f64 / looked.len() as f64 * count as f64).round() as usize,
        };
        let cause = Cause::of_images(
            JITTER.into(),
            "the camera rays look jittered, or aimed elsewhere inside their pixel: these \
                    differing pixels lie within what the reference takes inside their pixel"
                .into(),
            [explains, count, 0],
            (repair.first()).map(|&i| super::pixel_at(i, w, h)),
        );
        Some((cause, repaired, level_off.get()))
    })
}

/// Of the differing pixels a reading of jitter left (each outside what the reference
/// takes inside its pixel), how many lie at most a level above it and in no channel
/// below: a rule of the bytes beside jittered rays raises a byte by one
/// ([`rule_suspected`]).
#[derive(Debug, Clone, Copy, Default)]
struct LevelOff {
    near: usize,
    left: usize,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_jitter_check_s_sample_spans_the_columns() {
        // Its pixels' columns: at 4096x4096 the plain stride, 4096, is one column.
        let columns = |w: usize, h: usize| {
            let spread = spread_stride(w, h);
            let mut seen: Vec<usize> = (0..w * h).step_by(spread).map(|i| i % w).collect();
            seen.sort_unstable();
            seen.dedup();
            (spread, seen.len())
        };
        assert_eq!(columns(4096, 4096), (4097, 4096));
        // 640x480's 75 shares 5 with the width: 77, every column.
        assert_eq!(columns(640, 480), (77, 640));
        // 320x240's 19 shares nothing with it, and is kept.
        assert_eq!(columns(320, 240).0, 19);
    }

    #[test]
    fn a_first_cause_that_breaks_what_the_second_repairs_leaves_those_to_it() {
        // 100 pixels, 0..10 differing. Turned over, all ten agree and 10 and 11 differ;
        // with the clip too, all 100 agree. What the flip leaves is {10, 11}: the clip
        // makes both agree and breaks nothing.
        let found = |ids: &str, agreeing: usize, explains: usize, breaks: usize| Diagnosis {
            variants: ids
                .split(',')
                .map(|id| Variant::parse(id).unwrap())
                .collect(),
            agreement_before: 0.9,
            agreement_after: agreeing as f64 / 100.0,
            max_dist_range: None,
            pixel: Some([0, 0]),
            subject: None,
            trace: None,
            explains: Some(explains),
            breaks: Some(breaks),
            differing: Some(10),
        };
        let found = [
            found("upside-down,far-clip=10", 100, 10, 0),
            found("upside-down", 98, 10, 2),
            found("far-clip=10", 92, 2, 0),
        ];
        let told: Vec<(String, usize, usize, usize)> = (stated(&found, 10).into_iter())
            .map(|c| (c.id, c.explains, c.of, c.breaks))
            .collect();
        let expected = [("upside-down", 10, 10, 2), ("far-clip=10", 2, 2, 0)];
        assert_eq!(
            told,
            expected.map(|(id, e, o, b)| (id.to_string(), e, o, b))
        );
        // Where the pair breaks one of the pixels the flip broke, the clip is not stated
        // so: what it repairs is no longer all that the flip broke.
        let mut partly = found.clone();
        partly[0].breaks = Some(1);
        assert!(stated(&partly, 10).iter().all(|c| c.id != "far-clip=10"));
    }

    #[test]
    fn a_shifted_image_s_pixels_are_the_reference_s_from_where_they_come() {
        // Rendered whole under each move, every pixel whose ray lies inside the window
        // has the bytes of the reference's pixel that shifted_from names.
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/shadows.txt");
        let scene = crate::load(&std::fs::read_to_string(path).unwrap()).unwrap();
        let options = Options::new(48, 36);
        let reference = render::render(&scene, &options, |_| {});
        let moves = [
            "row-offset=2",
            "row-offset=-3",
            "column-offset=1",
            "upside-down",
        ];
        let pairs = [
            &["row-offset=-1", "column-offset=-2"][..],
            &["upside-down", "row-offset=1"],
        ];
        let cases = moves.iter().map(std::slice::from_ref).chain(pairs);
        for ids in cases {
            let moves: Vec<Variant> = ids.iter().map(|id| Variant::parse(id).unwrap()).collect();
            let moved = (moves.iter()).fold(options, |o, v| o.with_variant(*v).unwrap());
            let image = render::render(&scene, &moved, |_| {});
            let from = super::super::diagnose::shifted_from(&options, &moved, &moves).unwrap();
            let mut covered = 0;
            for (i, &bytes) in image.pixels.iter().enumerate() {
                if let Some(j) = from(i) {
                    assert_eq!(bytes, reference.pixels[j], "{ids:?} at {i}");
                    covered += 1;
                }
            }
            // Only the rows and columns past the window's edge are uncovered.
            assert!(covered >= 30 * 44, "{ids:?}: {covered}");
        }
    }
}
