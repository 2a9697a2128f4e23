//! `compare --diagnose`: which mistake explains a student's image.
//!
//! The candidates are spec §7.3's variants over the whole image, and the edits of one
//! record (spec §7.4, `ID@LINE`) on the objects and lights that the differing pixels'
//! paths involve (the first hit, the mirror's hits, the shadow rays' blockers, the lights
//! that reach them): a student's own mistake is most often one object or one light done
//! wrong. Each candidate is first tried on a sample, the differing pixels and as many
//! agreeing ones, rendered by the renderer's own code ([`super::render_pixels`]), which
//! estimates its agreement with the student's image (the share of pixels within the
//! tolerance); only the best is scored exactly, and what is reported is its exact
//! agreement. The best is tried together with each other candidate the same way.
//!
//! A candidate's bytes come from the renderer's code only where it can change them: the
//! reference keeps each pixel's paths ([`super::Paths`]: the objects hit, the shadows'
//! blockers, the lights, the bytes under the other byte rules), and a variant of one
//! record re-traces only the pixels whose paths name it ([`super::Reach`]); the others
//! keep the reference's bytes. Its exact agreement then costs the pixels it touches, not
//! a whole render (which the variants of the camera, the divisor or the geometry still
//! take).
//! MAX_DIST is not guessed from a list: one render with long paths records each pixel's
//! bytes after each mirror bounce ([`super::path_agreement`]), which gives the image
//! under every MAX_DIST at once, and the best D is read off ([`estimate_max_dist`]); the
//! same sweep on the large sample ([`super::path_agreement_at`]) first tells whether
//! that render is worth making.

use super::Reach;
use super::causes::{HALF, supported};
use super::{Reference, is_set, within};
use crate::render::trace::object_name;
use crate::render::variant::{Needs, Row, Scope, Site, output_row};
use crate::render::{self, Image, Kind, Options, VARIANTS, Variant};
use crate::scene::{Object, Scene};
use crate::shapes::Shape;
use serde::Serialize;

/// The longest MAX_DIST `--diagnose` considers: 30 times the course's 32.
pub const PROBE_LIMIT: f64 = 1000.0;

/// A share of the differing pixels of the large sample under which a candidate cannot be
/// a cause (it must explain half), whatever the sample's error: it is not rendered whole.
const HOPELESS: f64 = 0.4;

/// The variants of one continuous parameter, estimated from the pixels at round values.
const CONTINUOUS: [Kind; 3] = [Kind::FarClip, Kind::ZTolerance, Kind::ShadowEpsilon];

/// How many differing pixels, and as many agreeing ones, a candidate is tried on: every
/// candidate on the small sample first, the best [`SHORTLIST`] on the large one.
const SAMPLE: [usize; 2] = [128, 512];

/// How many candidates go on from the small sample to the large one.
const SHORTLIST: usize = 8;

/// How many of the candidates estimated alike best are scored exactly, where the first
/// makes agreeing pixels differ.
const TIED: usize = 6;

/// How many candidates after the best lend their mistakes to the image upside down and
/// an offset.
const RESTS: usize = 2;

/// How many of the partners estimated best (and alike) on the pixels a first leaves are
/// scored exactly, in turn, until one does better than the first alone.
const RANKED: usize = 3;

/// An agreement that explains the image: MAX_DIST is not estimated beyond it.
const EXPLAINED: f64 = 0.999;

/// The share of the gap to full agreement that MAX_DIST's best D must close on the large
/// sample before every pixel is rendered for it: well below the half a cause must explain,
/// for the sample's error (512 differing pixels: some 2 %).
const WORTH: f64 = 0.125;

/// How many of the objects and of the lights most involved in the differences are
/// tried with each edit of one record.
const SUBJECTS: usize = 4;

/// A variant, or two, that explains the student's image better than the reference.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Diagnosis {
    /// The variants, one or two; in JSON their ids, as `--variant` takes them.
    pub variants: Vec<Variant>,
    /// The reference's agreement with the student's image: the share of pixels within
    /// the tolerance.
    pub agreement_before: f64,
    /// The agreement of the reference rendered with the variants.
    pub agreement_after: f64,
    /// For max-dist=D: every D from the first number up to (not including) the second
    /// gives the same image.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_dist_range: Option<[f64; 2]>,
    /// A pixel (x, y from the lower left) the variants explain: it differs from the
    /// reference and agrees once they apply.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pixel: Option<[usize; 2]>,
    /// For a variant of one record: what it is, "cone (line 34)" or "light (line 7)".
    #[serde(skip_serializing_if = "Option::is_none")]
    pub subject: Option<String>,
    /// The command that traces `pixel` in the reference, when the command line knows the
    /// scene's file name.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub trace: Option<String>,
    /// How many of the differing pixels the variants make agree.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub explains: Option<usize>,
    /// How many agreeing pixels they make differ.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub breaks: Option<usize>,
    /// How many pixels differed before them.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub differing: Option<usize>,
}

/// Where the differences concentrate when no variant explains them: the object most
/// involved, and how the differing pixels' paths meet it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Focus {
    /// "cone (line 34)".
    pub object: String,
    /// Its index among the scene's objects.
    pub index: usize,
    /// The share of the (sampled) differing pixels whose path involves it (0 to 1).
    pub share: f64,
    /// Of those, the shares where the camera ray hits it, where it blocks a shadow ray,
    /// and where a mirror ray hits it.
    pub camera: f64,
    /// See `camera`.
    pub shadow: f64,
    /// See `camera`.
    pub mirror: f64,
    /// The light whose term the differences follow, where one does and no decision flip
    /// explains them.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub light: Option<LightFocus>,
    /// Where no light's term is followed, nearly every differing pixel's camera ray hits
    /// the object, most of the pixels whose camera or mirror rays hit it differ, and each
    /// channel differs one way on them (lighter, or darker), and no decision flip
    /// explains the differences: the share of those that differ, as when its colour is
    /// computed otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub material: Option<f64>,
}

/// A light whose term the differences follow: it lights nearly every (sampled) differing
/// pixel and few of the agreeing ones, as when it is not where the scene puts it or its
/// distance is computed otherwise.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LightFocus {
    /// "light (line 32)".
    pub light: String,
    /// Its index among the scene's lights.
    pub index: usize,
    /// The share of the sampled differing pixels it lights (0 to 1).
    pub differing: f64,
    /// The share of the sampled agreeing pixels it lights.
    pub agreeing: f64,
}

/// The share of the differing pixels a light must light for the differences to follow
/// it, at least.
const LIGHT_DIFFERING: f64 = 0.9;

/// The share of the agreeing pixels it may light, at most.
const LIGHT_AGREEING: f64 = 0.5;

/// The share of the differing pixels whose camera ray must hit one object for the
/// differences to follow its colour, at least.
const MATERIAL_CAMERA: f64 = 0.9;

/// The share of the pixels whose rays hit it that must differ, at least: far more than
/// an edge moved by a pixel changes.
const MATERIAL_DIFFERING: f64 = 0.5;

/// The share of the pixels where a channel differs that must differ the same way.
const MATERIAL_ONE_WAY: f64 = 0.95;

/// What one candidate scored.
#[derive(Clone)]
struct Tried {
    variants: Vec<Variant>,
    agreement: f64,
    max_dist_range: Option<[f64; 2]>,
    pixel: Option<usize>,
    /// The differing pixels it makes agree, and the agreeing ones it makes differ, where
    /// it was scored exactly.
    counts: Option<Counts>,
}

/// What a candidate does to the image, pixel by pixel: how many of the differing pixels
/// it makes agree, and how many of the agreeing ones it makes differ.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Counts {
    /// Differing pixels that agree under it.
    pub fixed: usize,
    /// Agreeing pixels that differ under it.
    pub broken: usize,
}

/// The variants that explain `student` better than `reference` (the image of `options`,
/// at `options`' size), best first; the best one together with another first where the
/// pair explains it better still. Empty when the images agree within `levels`
/// everywhere.
pub fn diagnose(
    scene: &Scene,
    options: &Options,
    reference: &Reference,
    student: &Image,
    levels: u8,
) -> Vec<Diagnosis> {
    diagnose_and_focus(scene, options, reference, student, levels).0
}

/// [`diagnose`], and where the differences concentrate ([`Focus`]) when they involve
/// objects.
pub fn diagnose_and_focus(
    scene: &Scene,
    options: &Options,
    rendered: &Reference,
    student: &Image,
    levels: u8,
) -> (Vec<Diagnosis>, Option<Focus>) {
    // Which pixels differ, a bit each (not a list of them all).
    let (mask, count) = super::differing(&rendered.image, student, levels);
    with_mask(
        scene,
        options,
        rendered,
        student,
        levels,
        (&mask, count),
        (&[], &[]),
    )
}

/// [`diagnose_and_focus`] given which pixels differ beyond `levels` (`mask`: pixel i is
/// bit i % 64 of word i / 64) and how many. The pixels set in `ignored` (empty: none),
/// which an earlier cause explains, count neither as fixed nor as broken; the variants of
/// the kinds in `leave_out`, which that cause stands for, are not tried.
pub(crate) fn with_mask(
    scene: &Scene,
    options: &Options,
    rendered: &Reference,
    student: &Image,
    levels: u8,
    (mask, differing): (&[u64], usize),
    (ignored, leave_out): (&[u64], &[Kind]),
) -> (Vec<Diagnosis>, Option<Focus>) {
    let reference = &rendered.image;
    let pixels = reference.pixels.len();
    let agreeing = pixels - differing;
    // `agreement(reference, student, levels)`, from the count.
    let before = agreeing as f64 / pixels.max(1) as f64;
    if before >= 1.0 {
        return (Vec::new(), None);
    }
    let agrees = |i: usize, bytes: [u8; 3]| within(bytes, student.pixels[i], levels);
    // The samples, every n-th differing and agreeing pixel. Each sample: its differing
    // pixels, then its agreeing ones, and where they start.
    let samples = SAMPLE.map(|n| {
        let every = |count: usize| count.div_ceil(n.max(1)).max(1);
        let mut sample = every_nth(mask, pixels, true, every(differing));
        let split = sample.len();
        let counted = |&i: &usize| ignored.get(i / 64).is_none_or(|w| w >> (i % 64) & 1 == 0);
        sample.extend(
            every_nth(mask, pixels, false, every(agreeing))
                .into_iter()
                .filter(counted),
        );
        (sample, split)
    });
    let total = reference.pixels.len() as f64;
    // What a candidate can change, where the reference knows its pixels' paths: only
    // those pixels are traced again, the others keep the reference's bytes (under its
    // byte rule). `None`: any pixel.
    let paths = &rendered.paths;
    let given: Vec<Variant> = options.variants.iter().collect();
    let reach = |variants: &[Variant]| match paths.len() == pixels {
        true => Reach::of(scene, &given, variants),
        false => None,
    };
    // The agreement a candidate would have, from its bytes on sample `k`; and the sample's
    // differing pixels it explains.
    let estimate_on = |k: usize, variants: &[Variant]| -> Option<(f64, Vec<usize>)> {
        let options = options.with_variants(variants).ok()?;
        let (sample, split) = &samples[k];
        let (sample_d, sample_a) = sample.split_at(*split);
        let bytes = match reach(variants) {
            Some(reach) => {
                let mut bytes = Vec::with_capacity(sample.len());
                let at = sample.iter().copied();
                reached(scene, &options, (reach, rendered), at, |_, b| bytes.push(b));
                bytes
            }
            None => super::render_pixels(scene, &options, sample),
        };
        let fixed: Vec<usize> = (sample_d.iter().zip(&bytes))
            .filter(|&(&i, &b)| agrees(i, b))
            .map(|(&i, _)| i)
            .collect();
        let kept = (sample_a.iter().zip(&bytes[sample_d.len()..]))
            .filter(|&(&i, &b)| agrees(i, b))
            .count();
        let share = |n: usize, of: usize| n as f64 / of.max(1) as f64;
        let after = differing as f64 * share(fixed.len(), sample_d.len())
            + agreeing as f64 * share(kept, sample_a.len());
        Some((after / total, fixed))
    };
    let scorer = Scorer {
        scene,
        options,
        rendered,
        student,
        levels,
        mask,
        differing,
        ignored,
        given: &given,
        untouched: Default::default(),
        retraced: Default::default(),
    };
    let exact_counts = |variants: &[Variant]| scorer.counts(variants);
    // The exact agreement, from the counts.
    let exact = |variants: &[Variant]| -> Option<(f64, Counts)> {
        let counts = exact_counts(variants)?;
        let agreeing = agreeing + counts.fixed - counts.broken;
        Some((agreeing as f64 / total.max(1.0), counts))
    };
    // Tried on the small sample, then the best few on the large one.
    let estimate = |variants: &[Variant]| estimate_on(1, variants);
    let shortlist = |candidates: &mut Vec<(Vec<Variant>, f64)>| {
        candidates.sort_by(|a, b| b.1.total_cmp(&a.1));
        candidates.truncate(SHORTLIST);
    };
    let (sample, split) = &samples[1];
    let paths = super::involved(scene, options, &sample[..*split]);
    let agreeing_paths = super::involved(scene, options, &sample[*split..]);
    // How each sampled differing pixel's channels differ: the student's less the
    // reference's.
    let moved: Vec<[i16; 3]> = (sample[..*split].iter())
        .map(|&i| {
            let (r, s) = (reference.pixels[i], student.pixels[i]);
            [0, 1, 2].map(|c| i16::from(s[c]) - i16::from(r[c]))
        })
        .collect();
    // The share of the pixels whose camera or mirror rays hit an object that differ:
    // counted on the reference's paths where it has them (every pixel, in one pass),
    // else estimated from the samples.
    let differing_where_hit = |object: usize| match rendered.paths.len() == pixels {
        true => {
            let (mut hit, mut differ) = (0usize, 0usize);
            for (i, path) in rendered.paths.iter().enumerate() {
                if path.may_hit(object) {
                    hit += 1;
                    differ += usize::from(is_set(mask, i));
                }
            }
            differ as f64 / hit.max(1) as f64
        }
        false => {
            let seen = |paths: &[super::Involved], count: usize| {
                let hit = paths.iter().filter(|p| p.hits.contains(&object)).count();
                count as f64 * hit as f64 / paths.len().max(1) as f64
            };
            let (d, a) = (seen(&paths, differing), seen(&agreeing_paths, agreeing));
            d / (d + a).max(1.0)
        }
    };
    let sampled = [&paths[..], &agreeing_paths[..]];
    let focus = focus(scene, sampled, &moved, &differing_where_hit);
    let held = options.all_variants();
    let mut candidates: Vec<Variant> = (Variant::tried()).filter(|v| !held.contains(v)).collect();
    candidates.extend(other_values());
    candidates.extend(stopped(scene));
    candidates.extend(scoped(scene, &paths));
    candidates.retain(|v| !leave_out.contains(&v.kind) && may_change(scene, options, v));
    // A move with each rule of the bytes, from the start: a row off whose bytes are
    // rounded agrees worse than the image as it is under either alone, so neither would
    // be the best to pair. The move is the one under which the reference's own pixels,
    // moved, agree best within one level on the large sample (no ray traced), where it
    // beats the image as it is. The sample holds as many differing pixels as agreeing
    // ones: each is weighed by the share of the image it stands for, so that the count
    // estimates the whole image's (an image upside down that is mostly black agrees
    // with the reference on few pixels, and moved on more).
    let rules = |v: &&Variant| matches!(v.kind, Kind::RoundBytes | Kind::Scale256);
    let within_one = |from: &dyn Fn(usize) -> Option<usize>| {
        let close = |&i: &usize| {
            let close = |j: usize| {
                super::pixel_difference(reference.pixels[j], student.pixels[i]) <= levels.max(1)
            };
            from(i).is_some_and(close)
        };
        let (sample, split) = &samples[1];
        let weight = sample_weight((sample, *split), (differing, agreeing));
        let (sample_d, sample_a) = sample.split_at(*split);
        let count = |part: &[usize]| part.iter().filter(|i| close(i)).count() as f64;
        count(sample_d) * weight(0) + count(sample_a) * weight(*split)
    };
    let as_it_is = within_one(&|i| Some(i));
    let shifts: Vec<Variant> = (candidates.iter())
        .filter(|v| SHIFTS.contains(&v.kind))
        .copied()
        .collect();
    // The best of `moves` (each a set of moves), with its count, where it beats the image
    // as it is.
    let best_of = |moves: &mut dyn Iterator<Item = Vec<Variant>>| {
        moves
            .filter_map(|moves| {
                let moved = options.with_variants(&moves).ok()?;
                let from = shifted_from(options, &moved, &moves)?;
                let near = within_one(&from);
                Some((moves, near))
            })
            .filter(|(_, n)| *n > as_it_is)
            .max_by(|a, b| a.1.total_cmp(&b.1))
    };
    let best_alone = best_of(&mut shifts.iter().map(|&m| vec![m]));
    let best_moved = best_alone.as_ref().map(|(moves, _)| moves[0]);
    // And the image upside down with each offset, where the pair beats every move alone:
    // a program that writes its rows from the top and one row off (d01 so moved was told
    // nothing; an offset alone agreed best, on 7 % of its pixels). Tried as the pair it
    // is; the searches below pair the best move alone. (Tried only where no move alone
    // brings half of the pixels within a level, it named every mistake of 104 of 374
    // images so moved, against 207: the flip alone does that where the offset changes
    // only the edges.)
    let flip = shifts.iter().find(|v| v.kind == Kind::UpsideDown).copied();
    let flipped_offsets = flip.into_iter().flat_map(|flip| {
        (shifts.iter())
            .filter(|v| v.kind != Kind::UpsideDown)
            .map(move |&offset| vec![flip, offset])
    });
    let two_moves = best_of(&mut flipped_offsets.into_iter())
        .filter(|(_, n)| best_alone.as_ref().is_none_or(|(_, alone)| n > alone))
        .map(|(moves, _)| moves);
    // An image upside down, as found above or, where no move brings the reference's
    // pixels within a level of the student's, hidden by a mistake of the colours
    // ([`hidden_flip`]). (Offsets paired so were chosen wrong: examples/studio.txt two
    // rows off without the division by the distance was paired with another offset and
    // told nothing.)
    let flipped = best_moved.filter(|m| m.kind == Kind::UpsideDown);
    let paired_move = flipped.or_else(|| {
        let flip = candidates.iter().find(|v| v.kind == Kind::UpsideDown)?;
        let moved = options.with_variant(*flip).ok()?;
        let from = shifted_from(options, &moved, &[*flip])?;
        hidden_flip(reference, student, &samples[1].0, &from).then_some(*flip)
    });
    // The pixel's centre moves every ray a little, so its pixels agree under it only with
    // the student's rule of the bytes: paired with each rule from the start too (spec1
    // with both agreed on 516 pixels under pixel-centre alone and was told jitter).
    let centre = (candidates.iter()).find(|v| v.kind == Kind::PixelCentre);
    // The moves paired so: the best alone, and the flip with an offset.
    let move_units: Vec<Vec<Variant>> = (best_moved.iter().map(|&m| vec![m]))
        .chain(two_moves.clone())
        .collect();
    let moves = move_units.iter().cloned();
    let moved_bytes = (moves.chain(centre.map(|&c| vec![c]))).flat_map(|moves| {
        (candidates.iter().filter(rules)).map(move |&r| [&moves[..], &[r]].concat())
    });
    let tried_first: Vec<Vec<Variant>> = (candidates.iter().map(|&v| vec![v]))
        .chain(two_moves.clone())
        .chain(moved_bytes)
        .collect();
    let first_try = |tried: Vec<Vec<Variant>>| -> Vec<(Vec<Variant>, f64)> {
        (tried.into_iter())
            .filter_map(|v| Some((estimate_on(0, &v)?.0, v)))
            .map(|(agreement, v)| (v, agreement))
            .filter(|(_, agreement)| *agreement > before)
            .collect()
    };
    let mut first_round = first_try(tried_first);
    // The move with the pixel's centre, where the move alone did no better than the image
    // as it is: a row off whose rays go through the pixels' centres agrees worse under
    // the offset alone, so no candidate was found to pair (d06 so at 160x120 was told
    // jitter and the offset).
    let tried = |moves: &Vec<Variant>| first_round.iter().any(|(v, _)| v == moves);
    let moved_centre: Vec<Vec<Variant>> = (move_units.iter())
        .filter(|moves| !tried(moves))
        .flat_map(|moves| centre.map(|&c| [&moves[..], &[c]].concat()))
        .collect();
    first_round.extend(first_try(moved_centre));
    // Where no candidate alone (nor the move with a rule of the bytes) is estimated to
    // explain half of the differing pixels, an image upside down is paired with every
    // other candidate: it and a mistake of the colours that changes nearly every lit
    // pixel hide each other (a room of walls upside down whose light falls off with the
    // square of the distance: under either alone no pixel agrees, and it was told
    // nothing). An offset of a few rows or columns leaves most rays near where they were,
    // so that the mistake of the colours alone explains most pixels and the offset is
    // found as its partner.
    let half = before + (1.0 - before) * HALF;
    if let Some(m) = paired_move
        && first_round.iter().all(|(_, agreement)| *agreement < half)
    {
        let pairs = (candidates.iter())
            .filter(|v| !SHIFTS.contains(&v.kind) && !rules(v))
            .map(|&v| vec![m, v]);
        first_round.extend(first_try(pairs.collect()));
    }
    // An object missing from the scene as the program holds it (its record skipped, or
    // left out of every ray): seen by neither camera nor shadow rays. Where no candidate
    // alone explains half, each object hidden from the camera is tried hidden from the
    // shadow rays too: what its absence shows may lie in its own shadow
    // (examples/tiled_planes.txt without its floor shows the wall below it, which the
    // floor shades: under either alone no pixel agrees).
    if first_round.iter().all(|(_, agreement)| *agreement < half) {
        let absent = (candidates.iter())
            .filter(|v| v.kind == Kind::Hidden && v.line.is_some())
            .map(|&v| {
                let unshadowed = Variant {
                    kind: Kind::NoShadow,
                    ..v
                };
                vec![v, unshadowed]
            })
            .filter(|pair| may_change(scene, options, &pair[1]));
        first_round.extend(first_try(absent.collect()));
        // And the light's falloff squared with the division by the distance left out or
        // taken otherwise: each alone changes every lit pixel, and neither makes one
        // agree (examples/tiled_planes.txt so was told nothing).
        let falloff = (candidates.iter())
            .find(|v| v.kind == Kind::SquareFalloff && v.line.is_none())
            .copied();
        let divisors = (candidates.iter())
            .filter(|v| matches!(v.kind, Kind::NoDistance | Kind::SegmentDistance));
        let terms = falloff
            .into_iter()
            .flat_map(|f| divisors.clone().map(move |&d| vec![d, f]));
        first_round.extend(first_try(terms.collect()));
    }
    // More candidates near the best of a kind: each tried on the small sample, kept
    // where it does better than the image as it is.
    let try_near = |near: Vec<Variant>,
                    first_round: &mut Vec<(Vec<Variant>, f64)>,
                    candidates: &mut Vec<Variant>| {
        let near: Vec<Variant> = near
            .into_iter()
            .filter(|v| !candidates.contains(v))
            .collect();
        first_round.extend(
            (near.iter())
                .filter_map(|&v| Some((vec![v], estimate_on(0, &[v])?.0)))
                .filter(|(_, agreement)| *agreement > before),
        );
        candidates.extend(near);
    };
    // A reader that stopped, tried at every record near the best of the stops tried.
    let stops_tried = first_round
        .iter()
        .filter(|(v, _)| v[0].kind == Kind::StoppedAt);
    if let Some(line) = stops_tried
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .and_then(|(v, _)| v[0].line)
    {
        try_near(stopped_near(scene, line), &mut first_round, &mut candidates);
    }
    // A continuous parameter (far-clip=D, z-tolerance=E, shadow-epsilon=E) is tried at a
    // few round values first; where the best of them does better than the image as it
    // is, the round values between its neighbours are tried too, the roundest first, so
    // that among equals the one a student would write is kept (30, not 29.7). Values on
    // either side of the student's may agree alike (each gets part of the pixels right):
    // the range searched spans every value that ties with the best.
    for kind in CONTINUOUS {
        let of_kind = |v: &Variant| v.kind == kind && v.line.is_none();
        let tried: Vec<(f64, f64)> = (first_round.iter())
            .filter(|(v, _)| v.len() == 1 && of_kind(&v[0]))
            .filter_map(|(v, agreement)| Some((v[0].value?, *agreement)))
            .collect();
        let values: Vec<f64> = (candidates.iter())
            .filter(|v| of_kind(v))
            .filter_map(|v| v.value)
            .collect();
        let mut near = values_near(kind, &tried, values);
        // A shadow epsilon none of whose first values does better than the image as it
        // is (0.4 in examples/shadows.txt at 160x120 lights the 35 pixels whose casters
        // lie within 0.4 of the surface, and 0.1 none of them): estimated from how far
        // the sampled pixels' blockers lie.
        let epsilon = kind == Kind::ShadowEpsilon && candidates.iter().any(of_kind);
        if epsilon && tried.is_empty() {
            let (sample, split) = &samples[1];
            let counts = (differing, agreeing);
            near.extend(estimate_epsilon(scene, options, (sample, *split), counts));
        }
        try_near(near, &mut first_round, &mut candidates);
    }
    shortlist(&mut first_round);
    // The pixel to show `variants` by, of the sample's differing pixels they fix (in pixel
    // order): the first not among `not` (sorted), and not one an offset leaves uncovered,
    // which shows what a buffer held, not the ray.
    let pixel_of = |variants: &[Variant], fixed: &[usize], not: &[usize]| {
        let shown = options.with_variants(variants).ok().map(|o| uncovered(&o));
        let covered = || {
            fixed
                .iter()
                .filter(|&&i| !shown.as_ref().is_some_and(|s| s(i)))
        };
        (covered().find(|i| not.binary_search(i).is_err()))
            .or(covered().next())
            .or(fixed.first())
            .copied()
    };
    // Each with how many of the large sample's differing pixels it fixes.
    let mut estimated: Vec<(Tried, usize)> = (first_round.into_iter())
        .filter_map(|(variants, _)| {
            let (agreement, fixed) = estimate(&variants)?;
            let pixel = pixel_of(&variants, &fixed, &[]);
            let tried = Tried {
                pixel,
                variants,
                agreement,
                max_dist_range: None,
                counts: None,
            };
            (agreement > before).then_some((tried, fixed.len()))
        })
        .collect();
    // Best first; a stable sort keeps the table's order among equals.
    estimated.sort_by(|a, b| b.0.agreement.total_cmp(&a.0.agreement));
    // One cause's variants (one variant, or the moves of an image upside down and an
    // offset) scored exactly, for the causes' order, with the first pixel of the large
    // sample it fixes where `pixel`.
    let alone = |one: &[Variant], pixel: bool| {
        let (agreement, counts) = exact(one)?;
        let fixed = || estimate(one).and_then(|(_, fixed)| pixel_of(one, &fixed, &[]));
        Some(Tried {
            variants: one.to_vec(),
            agreement,
            max_dist_range: None,
            pixel: if pixel { fixed() } else { None },
            counts: Some(counts),
        })
    };
    // The best estimate rendered whole: its agreement is the one reported. Not one that
    // moves every ray a little (the pixel's centre, the kernel: a render of every pixel,
    // whose image differs from the reference's at edges and fragile pixels only) where
    // the large sample shows it cannot be a cause: it fixes under [`HOPELESS`] of the
    // sample's differing pixels (all of them, where they are fewer than the sample holds;
    // of 512, some 2 % either way). Jittered rays' images rendered so gained nothing.
    // The best of the others is rendered instead: jittered rays without shadows in d04
    // had jitter first, under two fifths, and were told nothing; no-shadows, next, finds
    // jitter as its partner.
    let hopeless = |(tried, fixed): &(Tried, usize)| {
        let whole = |v: &Variant| {
            let site = v.kind.row().site;
            (site == Site::Camera && !SHIFTS.contains(&v.kind)) || site == Site::Option
        };
        let few = (*fixed as f64) < HOPELESS * samples[1].1 as f64;
        few && tried.variants.iter().all(whole) && reach(&tried.variants).is_none()
    };
    let mut found: Vec<Tried> = Vec::new();
    // Of those that tie with the best estimate, the first scored exactly, and where it
    // moves no pixel and makes agreeing pixels differ that the sample does not hold, the
    // next few too (a move has its own searches below): the best of them is kept, the
    // first of equals (examples/spheres.txt drawn with a shadow
    // epsilon of 2 was told no-shadows, which lights its 21 pixels and 3 more; the epsilon,
    // tied with it on the samples, lights the 21 alone).
    let mut ranked = (estimated.into_iter()).filter(|t| !hopeless(t));
    let first = ranked.next().and_then(|(tried, _)| {
        let (agreement, counts) = exact(&tried.variants)?;
        Some((tried, agreement, counts))
    });
    let first = first.map(|(mut best, mut agreement, mut counts)| {
        let moves = best.variants.iter().any(|v| SHIFTS.contains(&v.kind));
        if counts.broken > 0 && !moves {
            let estimated = best.agreement;
            // Other values of the best's own kinds are not other explanations: the
            // samples cannot part a far clip of 6 from one of 9 (d05 a row off and
            // clipped at 10), and the values were searched for above.
            let kinds: Vec<Kind> = best.variants.iter().map(|v| v.kind).collect();
            let other = |t: &(Tried, usize)| t.0.variants.iter().all(|v| !kinds.contains(&v.kind));
            let tied = (ranked.take_while(|t| t.0.agreement >= estimated))
                .filter(other)
                .take(TIED - 1);
            for (tried, _) in tied {
                if let Some((a, c)) = exact(&tried.variants)
                    && a > agreement
                {
                    (best, agreement, counts) = (tried, a, c);
                }
            }
        }
        (best, agreement, counts)
    });
    if let Some((tried, agreement, counts)) = first
        && agreement > before
    {
        let pair = tried.variants.clone();
        found.push(Tried {
            agreement,
            counts: Some(counts),
            ..tried
        });
        // A move (or an image upside down and an offset) with a rule of the bytes: each
        // cause alone too, for the causes' order.
        let units = units(&pair);
        if let [_, _] = units[..] {
            found.extend(units.into_iter().filter_map(|one| alone(one, true)));
        }
    }
    // MAX_DIST can change only the pixels whose path reflects: it is estimated (at the
    // cost of a render) only where fixing every differing one of them would agree better
    // than the best found so far.
    let reflected = paths.iter().filter(|path| path.reflected).count();
    let at_most = before + (1.0 - before) * reflected as f64 / paths.len().max(1) as f64;
    let best = found.iter().map(|t| t.agreement).fold(before, f64::max);
    // And first on the large sample: only a D that closes a good part of the gap there is
    // worth the render of every pixel.
    let worth_rendering = || {
        let (sample, split) = &samples[1];
        let (state, changes) =
            super::path_agreement_at(scene, &probe(options), sample, |k, b| agrees(sample[k], b));
        let weight = sample_weight((sample, *split), (differing, agreeing));
        best_max_dist(&state, &changes, weight, options.max_dist)
            .is_some_and(|(_, _, agreeing)| agreeing / total > best + (1.0 - best) * WORTH)
    };
    if reflected > 0
        && at_most > best
        && best < EXPLAINED
        && worth_rendering()
        && let Some((d, range, agreement, pixel)) =
            estimate_max_dist(scene, options, student, levels)
        && agreement > before
    {
        found.push(Tried {
            variants: vec![Variant {
                value: Some(d),
                ..Variant::of(Kind::MaxDist)
            }],
            agreement,
            max_dist_range: Some(range),
            pixel,
            counts: None,
        });
    }
    // Best first; of equals, the fewer variants (a move paired with a rule of the bytes
    // that moves nothing the student's image shows is the rule alone, whose own partner
    // is then looked for: a02 stopped at its floor, with its bytes scaled by 256).
    found.sort_by(|a, b| {
        (b.agreement.total_cmp(&a.agreement)).then(a.variants.len().cmp(&b.variants.len()))
    });
    // The best one with each other candidate: a second mistake often shows only once the
    // first is undone (an image upside down hides everything else).
    if let Some(best) = found.first().filter(|best| best.agreement < 1.0).cloned() {
        // Its first cause: one variant, or an image upside down and an offset.
        let first = units(&best.variants)[0].to_vec();
        let with = |partner: Variant| [&first[..], &[partner]].concat();
        let mut estimated = found.iter().map(|t| t.variants[0]);
        let max_dist = estimated.rfind(|v| v.kind == Kind::MaxDist);
        let partners = candidates.iter().copied().chain(max_dist);
        let partners: Vec<Variant> =
            (partners.filter(|p| first.iter().all(|f| p.id() != f.id()))).collect();
        // Under a first that only moves the pixels (a row off, upside down), the partner
        // is looked for on the pixels it leaves, where the samples of every differing
        // pixel would hold a handful.
        // A partner that, with the first, does better than the first alone, scored
        // exactly: with its estimate, the pixels of the large sample it fixes, and the
        // pair's exact agreement and counts.
        let better = |top: Option<(Variant, (f64, Vec<usize>))>| {
            let (partner, (_, fixed)) = top.filter(|t| t.1.0 > best.agreement)?;
            let (agreement, counts) = exact(&with(partner))?;
            (agreement > best.agreement).then_some((partner, fixed, agreement, counts))
        };
        // Of partners estimated on the pixels the first leaves, best first: those that tie
        // with the best scored exactly, up to a few, until one does better. Two may tie
        // there and not on the whole image (d06 a column off, stopped at line 58: a stop
        // at 48 fixes the 43 pixels too, and breaks others the sample does not hold).
        // Where the one found leaves differing pixels or breaks agreeing ones, the next
        // few that tie with it and are of other kinds are scored too, and the best kept
        // (the first of equals): examples/spheres.txt a row off with a shadow epsilon of
        // 2, whose 21 pixels the samples hold, tied no-shadows (18 of 21), a sphere and a
        // light unshadowed, and the epsilon (21 of 21).
        let better_of = |ranked: Vec<(Variant, (f64, Vec<usize>))>| {
            let best = ranked.first().map_or(0.0, |t| t.1.0);
            let mut tied = (ranked.into_iter()).take_while(|t| t.1.0 >= best);
            let mut kinds = Vec::new();
            let mut found = (tied.by_ref().take(RANKED)).find_map(|top| {
                kinds.push(top.0.kind);
                better(Some(top))
            })?;
            let whole = |counts: Counts| counts.fixed >= differing && counts.broken == 0;
            let mut more = 0;
            for top in tied {
                if whole(found.3) || more == TIED - 1 {
                    break;
                }
                if kinds.contains(&top.0.kind) {
                    continue;
                }
                kinds.push(top.0.kind);
                more += 1;
                if let Some(other) = better(Some(top)).filter(|o| o.2 > found.2) {
                    found = other;
                }
            }
            Some(found)
        };
        let shift = first.iter().all(|v| SHIFTS.contains(&v.kind));
        let top = match shift.then(|| scorer.left(&first)).flatten() {
            Some(left) => better_of(scorer.best_partners(&first, partners, &left)),
            None => {
                let mut pairs: Vec<(Vec<Variant>, f64)> = (partners.iter())
                    .filter_map(|&partner| Some((with(partner), estimate_on(0, &with(partner))?.0)))
                    .collect();
                shortlist(&mut pairs);
                let pairs = (pairs.into_iter())
                    .filter_map(|(pair, _)| Some((*pair.last()?, estimate(&pair)?)));
                let top =
                    pairs.max_by(|a, b| a.1.0.total_cmp(&b.1.0).then(std::cmp::Ordering::Greater));
                // A first that explains nearly all leaves too few pixels for the samples of
                // every differing pixel to hold one: where they show no partner, or one
                // that explains under half of what the first leaves, it is looked for on
                // the pixels the first leaves (d06 stopped at line 58, its bytes scaled by
                // 256: 43 pixels of 32,607; spec1 under pixel-centre with a z tolerance of
                // 0.1, found as 0.01 on 7 of the 58).
                let general = better(top);
                let (first_fixed, first_broken) =
                    best.counts.map_or((0, 0), |c| (c.fixed, c.broken));
                // So too where the partner is a shadow left out that leaves some of them: an
                // epsilon lights only the shadows whose casters lie within it and keeps
                // the others, which no removal of shadows keeps, and its estimate is made
                // on the pixels the first leaves (examples/spheres.txt with an epsilon of
                // 2 beside no-distance, a rule of the bytes or the falloff squared:
                // no-shadows, 18 of the 21, was stated; it lights 3 the epsilon keeps).
                let unshadowing = |v: &Variant| {
                    matches!(v.kind, Kind::NoShadows | Kind::NoShadow | Kind::Unshadowed)
                };
                let weak = general.as_ref().is_none_or(|(partner, _, _, counts)| {
                    let explains = counts.fixed.saturating_sub(first_fixed);
                    let breaks = counts.broken.saturating_sub(first_broken);
                    let of = differing - first_fixed.min(differing);
                    let part = explains < of || breaks > 0;
                    !supported(explains, of, breaks) || (unshadowing(partner) && part)
                });
                let on_left = weak
                    .then(|| {
                        let left = scorer.left(&first)?;
                        better_of(scorer.best_partners(&first, partners, &left))
                    })
                    .flatten();
                [general, on_left]
                    .into_iter()
                    .flatten()
                    .max_by(|a, b| a.2.total_cmp(&b.2).then(std::cmp::Ordering::Greater))
            }
        };
        if let Some((partner, fixed, agreement, counts)) = top {
            // The pair's pixel: one the first alone leaves, so that it shows the partner
            // (the samples are in pixel order).
            let alone_fixed = estimate(&first).map_or(Vec::new(), |(_, fixed)| fixed);
            let pixel = (fixed.iter().find(|i| alone_fixed.binary_search(i).is_err()))
                .or(fixed.first())
                .copied();
            let range = match (first[0].kind, partner.kind) {
                (Kind::MaxDist, _) => best.max_dist_range,
                (_, Kind::MaxDist) => found.iter().find_map(|t| t.max_dist_range),
                _ => None,
            };
            let pair = Tried {
                variants: with(partner),
                agreement,
                max_dist_range: range,
                pixel,
                counts: Some(counts),
            };
            found.insert(0, pair);
            // The partner alone too: which of the two comes first is what each explains
            // alone (a whole-image mistake may hide the other's pixels).
            if !found.iter().any(|t| t.variants == [partner]) {
                found.extend(alone(&[partner], false));
            }
        }
    }
    // A continuous parameter estimated alone in an image also moved is the value whose
    // edge the move leaves in place (a far clip of 10 in an image a row off is found as 9,
    // or 6): where the best candidate holds one and a move agrees better than the image
    // as it is, the parameter is estimated again under the move, and the move's best
    // partner is looked for.
    // The same where the best candidate explains too little and its first is not the
    // move, whose best partner the pair stage then looked for (a reader stopped at a far
    // wall, with or without the image turned over, in an image upside down whose far wall
    // is clipped): the move's best partner is looked for, and the parameter is not.
    // A pair found by a search below, with its estimate and the large sample's pixels it
    // fixes, kept where it agrees better than `than` (estimated, then exactly): listed
    // first, with a pixel that `kept` alone leaves (so that it shows the other), and each
    // of its causes alone ([`units`]) for the causes' order.
    type Estimated = ((f64, Vec<usize>), Vec<Variant>);
    let adopt = |found: &mut Vec<Tried>,
                 than: f64,
                 ((estimated, fixed), pair): Estimated,
                 kept: &[Variant]| {
        if estimated <= than {
            return;
        }
        let Some((agreement, counts)) = exact(&pair).filter(|(a, _)| *a > than) else {
            return;
        };
        let alone_fixed = estimate(kept).map_or(Vec::new(), |(_, fixed)| fixed);
        let pixel = pixel_of(&pair, &fixed, &alone_fixed);
        let tried = Tried {
            variants: pair.clone(),
            agreement,
            max_dist_range: None,
            pixel,
            counts: Some(counts),
        };
        found.insert(0, tried);
        for one in units(&pair) {
            if !found.iter().any(|t| t.variants == one) {
                found.extend(alone(one, true));
            }
        }
    };
    let continuous = |v: &&Variant| CONTINUOUS.contains(&v.kind) && v.line.is_none();
    // The move: the image upside down and an offset where that pair beat every move alone
    // (spec1 so, clipped at 10, was told far-clip=5.1: the clip estimated where the
    // offset leaves its edge; d06 so, a reader that stopped at line 8).
    let unit = two_moves.clone().or(best_moved.map(|m| vec![m]));
    if let Some(m) = unit
        && let Some(top) = found.first().filter(|t| t.agreement < 1.0).cloned()
        && let Some(value) = match top.variants.iter().find(continuous) {
            Some(&value) => Some(Some(value)),
            None => (!top.variants.starts_with(&m) && top.agreement < EXPLAINED).then_some(None),
        }
    {
        // The move's own best partner, looked for on the pixels it leaves: the parameter
        // may stand for another mistake (a far object hidden, as a far clip).
        let partners = (candidates.iter().copied()).filter(|p| m.iter().all(|m| p.id() != m.id()));
        let with = |v: Variant| [&m[..], &[v]].concat();
        let by_partner = (scorer.left(&m))
            .and_then(|left| {
                (scorer
                    .best_partners(&m, partners.collect(), &left)
                    .into_iter())
                .next()
            })
            .map(|(partner, estimated)| (estimated, with(partner)));
        // And, unless that explains the image, the parameter under the move: its first
        // values and the one found alone, then the round values near the best of those.
        let explained = by_partner.as_ref().is_some_and(|(e, _)| e.0 >= EXPLAINED);
        let under = with;
        let by_value = |value: Variant| {
            let kind = value.kind;
            let firsts = (other_values().into_iter())
                .filter(|v| v.kind == kind)
                .chain([value]);
            let mut round: Vec<(Vec<Variant>, f64)> = firsts
                .filter_map(|v| Some((under(v), estimate_on(0, &under(v))?.0)))
                .collect();
            let tried: Vec<(f64, f64)> = (round.iter())
                .filter_map(|(v, agreement)| Some((v.last()?.value?, *agreement)))
                .collect();
            let values = tried.iter().map(|t| t.0).collect();
            round.extend(
                (values_near(kind, &tried, values).into_iter())
                    .filter_map(|v| Some((under(v), estimate_on(0, &under(v))?.0))),
            );
            shortlist(&mut round);
            (round.into_iter())
                .filter_map(|(pair, _)| Some((estimate(&pair)?, pair)))
                .collect::<Vec<_>>()
        };
        let by_value = match value.filter(|_| !explained) {
            Some(value) => by_value(value),
            None => Vec::new(),
        };
        let best = (by_value.into_iter().chain(by_partner))
            .max_by(|a, b| a.0.0.total_cmp(&b.0.0).then(std::cmp::Ordering::Greater));
        if let Some(best) = best {
            adopt(&mut found, top.agreement, best, &m);
        }
    }
    // A reader that stopped before its lights changes nearly every pixel, and a move of
    // the image besides leaves none of the reference's where the student has it: no
    // move agrees better than the image as it is, and no stop alone does much (d05 read
    // up to line 73 and written upside down: the best single, a far clip, explained 45 %).
    // Where nothing found explains half of the differing pixels, each move is tried
    // beside each stop tried alone, on the small sample, the best few on the large one.
    let weak = found.first().is_none_or(|t| {
        let explains = t.counts.map_or(0, |c| c.fixed);
        !supported(explains, differing, t.counts.map_or(0, |c| c.broken))
    });
    // Of `pairs`, those that do better than the image as it is on the small sample, the
    // best few on the large one: the best there, with its estimate.
    let best_pair = |pairs: Vec<Vec<Variant>>| -> Option<Estimated> {
        let mut round: Vec<(Vec<Variant>, f64)> = (pairs.into_iter())
            .filter_map(|pair| Some((estimate_on(0, &pair)?.0, pair)))
            .map(|(agreement, pair)| (pair, agreement))
            .filter(|(_, agreement)| *agreement > before)
            .collect();
        shortlist(&mut round);
        (round.into_iter())
            .filter_map(|(pair, _)| Some((estimate(&pair)?, pair)))
            .max_by(|a, b| a.0.0.total_cmp(&b.0.0).then(std::cmp::Ordering::Greater))
    };
    if weak {
        let moves = (candidates.iter()).filter(|v| SHIFTS.contains(&v.kind) && v.line.is_none());
        let pairs = moves
            .flat_map(|&m| stopped(scene).into_iter().map(move |stop| vec![m, stop]))
            .collect();
        let than = found.first().map_or(before, |t| t.agreement);
        if let Some(best) = best_pair(pairs) {
            let stop = best.1[1];
            adopt(&mut found, than, best, &[stop]);
        }
    }
    // A reader's stop found beside another mistake is the line where the two together
    // agree best, which need not be the stop that agreed best alone (spec1 stopped at
    // line 42 with its far objects clipped was found as a stop at 30, the clip hiding
    // what the records from 30 on add): every stop is tried beside the partner, on the
    // small sample, the best few on the large one, and the best of those scored exactly.
    let pair_first = (found.first()).filter(|t| t.agreement < 1.0 && t.variants.len() == 2);
    if let Some(top) = pair_first.cloned()
        && let Some(k) = (top.variants.iter()).position(|v| v.kind == Kind::StoppedAt)
    {
        let with_stop = |stop: Variant| {
            let mut pair = top.variants.clone();
            pair[k] = stop;
            pair
        };
        let pairs = (stops(scene).into_iter())
            .map(|line| Variant::of(Kind::StoppedAt).at(line))
            .filter(|&stop| stop != top.variants[k])
            .map(with_stop)
            .collect();
        if let Some(best) = best_pair(pairs) {
            let partner = top.variants[1 - k];
            adopt(&mut found, top.agreement, best, &[partner]);
        }
    }
    // A continuous parameter found beside another mistake was estimated on the samples
    // of every differing pixel, which hold few of the pixels the other leaves (spec1
    // under pixel-centre with a z tolerance of 0.1, at 640x480: 198 of 82,572, and 0.05,
    // which explains 100 of them, was found): its values are tried again beside the
    // other on the pixels the other leaves, the first values of its kind and the round
    // ones near the best, and the best scored exactly.
    let pair_first = (found.first()).filter(|t| t.agreement < 1.0 && t.variants.len() == 2);
    if let Some(top) = pair_first.cloned()
        && let Some(k) = (top.variants.iter()).position(|v| continuous(&v))
        && let Some(left) = scorer.left(&top.variants[1 - k..2 - k])
    {
        let (other, kind) = (top.variants[1 - k], top.variants[k].kind);
        let values = (other_values().into_iter())
            .filter(|v| v.kind == kind)
            .chain([top.variants[k]])
            .collect();
        let ranked = scorer.best_partners(&[other], values, &left);
        let best = (ranked.into_iter())
            .filter(|(v, _)| v.kind == kind && v.line.is_none())
            .find(|(v, _)| *v != top.variants[k]);
        if let Some((value, estimated)) = best {
            let mut pair = top.variants.clone();
            pair[k] = value;
            adopt(&mut found, top.agreement, (estimated, pair), &[other]);
        }
    }
    // An image upside down found beside another mistake (hidden by it, [`hidden_flip`]) may
    // also be a row or column off: the flip was paired alone, and what the offset leaves
    // was read as jitter (d03 upside down, a row off and without the division by the
    // distance at 160x120: the flip and no-distance explained 3,500 of 3,623, jitter 113
    // of the 123 left). So too the flip found with an offset by the moves' search, where
    // the other mistake hides which (d04 upside down, two rows back, without the division:
    // one column off, 10,490 of 19,070), and one mistake found alone, whose colours hid
    // the flip from both searches (d01 so: no-distance, 16,522 of 18,982). The flip is
    // tried with each other offset beside the rest, and the best scored exactly.
    let refined = |t: &&Tried| {
        let moves: Vec<Kind> = (t.variants.iter())
            .filter(|v| SHIFTS.contains(&v.kind))
            .map(|v| v.kind)
            .collect();
        let flipped = moves.first() == Some(&Kind::UpsideDown) && moves.len() <= 2;
        let alone = moves.len() <= 1 && t.variants.len() <= 2;
        // The flip and an offset alone, whose partner only the next candidates hold.
        let moves_only = flipped && moves.len() == 2 && t.variants.len() == 2;
        let beside = moves.len() < t.variants.len() && (flipped || alone);
        t.agreement < 1.0 && (beside || moves_only)
    };
    if let Some(top) = found.first().filter(refined).cloned()
        && let Some(flip) = flip
    {
        let split = |t: &Tried| -> (Vec<Variant>, Vec<Variant>) {
            (t.variants.iter()).partition(|v| SHIFTS.contains(&v.kind))
        };
        let (moves, rest) = split(&top);
        // The rest of the next candidates too, where the best is no cause: it may pair an
        // offset with another mistake by chance (examples/spheres.txt upside down, a row
        // off and lit with the square of the distance was best explained as a row back
        // with a reader stopped at line 11, 272 of 895; the flip with square-falloff came
        // next). A best that is a cause leaves no room for the next ones'.
        let weak = (top.counts).is_none_or(|c| !supported(c.fixed, differing, c.broken));
        let mut rests = vec![rest];
        for next in found.iter().skip(1).take(if weak { RESTS } else { 0 }) {
            let (_, rest) = split(next);
            if !rest.is_empty() && !rests.contains(&rest) {
                rests.push(rest);
            }
        }
        // The flip and an offset alone: their own best partner too, on the pixels they
        // leave (examples/spheres.txt upside down, two rows off, lit with the square of
        // the distance: the next candidates were the flip with one record hidden).
        let own_partner = (rests[0].is_empty())
            .then(|| {
                let partners = (candidates.iter().copied())
                    .filter(|p| !SHIFTS.contains(&p.kind))
                    .collect();
                let left = scorer.left(&moves)?;
                let ranked = scorer.best_partners(&moves, partners, &left);
                Some(ranked.into_iter().next()?.0)
            })
            .flatten();
        rests.extend(own_partner.map(|partner| vec![partner]));
        let offsets = (shifts.iter()).filter(|v| v.kind != Kind::UpsideDown);
        let moved: Vec<Vec<Variant>> = (offsets.map(|&offset| [flip, offset]))
            .flat_map(|pair| {
                let own = moves == pair;
                (rests.iter().enumerate())
                    .filter(move |&(k, rest)| (k > 0 || !own) && !rest.is_empty())
                    .map(move |(_, rest)| [&pair[..], rest].concat())
            })
            .collect();
        if let Some(best) = best_pair(moved) {
            let kept: Vec<Variant> = (best.1.iter())
                .filter(|v| !SHIFTS.contains(&v.kind))
                .copied()
                .collect();
            adopt(&mut found, top.agreement, best, &kept[..1]);
        }
    }
    // The counts of the one that went without (MAX_DIST's), for the causes.
    for tried in &mut found {
        if tried.counts.is_none() {
            tried.counts = exact_counts(&tried.variants);
        }
    }
    let (width, height) = (reference.width.max(1), reference.height);
    let diagnoses = found
        .into_iter()
        .map(|tried| Diagnosis {
            subject: subject(scene, &tried.variants),
            variants: tried.variants,
            agreement_before: before,
            agreement_after: tried.agreement,
            max_dist_range: tried.max_dist_range,
            pixel: (tried.pixel).map(|i| super::pixel_at(i, width, height)),
            trace: None,
            explains: tried.counts.map(|c| c.fixed),
            breaks: tried.counts.map(|c| c.broken),
            differing: Some(differing),
        })
        .collect();
    (diagnoses, focus)
}

/// `each(i, bytes)` for the pixels `i` of `at` (output order) of the image under
/// `options`, a candidate that changes only what `reach` touches: those pixels traced
/// again, the others the reference's (stepped under a byte rule).
fn reached(
    scene: &Scene,
    options: &Options,
    (reach, rendered): (Reach, &Reference),
    at: impl Iterator<Item = usize> + Clone,
    mut each: impl FnMut(usize, [u8; 3]),
) {
    let paths = &rendered.paths;
    // A byte rule alone traces nothing (and sets up no renderer).
    if !reach.traces() {
        for i in at {
            each(i, reach.untouched(paths[i], rendered.image.pixels[i]));
        }
        return;
    }
    let traced: Vec<usize> = at.clone().filter(|&i| reach.touches(paths[i])).collect();
    let mut bytes = super::render_pixels(scene, options, &traced).into_iter();
    for i in at {
        let pixel = match reach.touches(paths[i]) {
            true => bytes.next().unwrap_or_default(),
            false => reach.untouched(paths[i], rendered.image.pixels[i]),
        };
        each(i, pixel);
    }
}

/// Whether the reference upside down (`from`) is nearer the student's pixel than the
/// reference as it is (the sum of the channels' differences), on the pixels `sample`, on
/// at least five for every four it is farther on, and on a tenth of them at least
/// ([`HIDDEN_FLIP`]): an image upside down whose colours a mistake changes everywhere
/// still shows each object's pixels nearer their own colours than another object's (d05
/// upside down with its light falling off with the square of the distance: 401 pixels
/// nearer, 102 farther, of 506; examples/studio.txt so, whose mirrors and tiles show
/// other objects' colours: 297 nearer, 210 farther). An offset of a few rows or columns
/// leaves most rays near where they were, so that the mistake of the colours alone
/// explains most pixels and the offset is found as its partner; offsets judged so were
/// chosen wrong (a smooth image a row off is nearer the student's under the neighbouring
/// offsets too: spec1 two rows off without the division by the distance was paired with
/// one row off and told nothing).
fn hidden_flip(
    reference: &Image,
    student: &Image,
    sample: &[usize],
    from: &dyn Fn(usize) -> Option<usize>,
) -> bool {
    let apart =
        |a: [u8; 3], b: [u8; 3]| -> u32 { (0..3).map(|c| u32::from(a[c].abs_diff(b[c]))).sum() };
    let [mut nearer, mut farther] = [0, 0];
    for &i in sample {
        let Some(j) = from(i) else { continue };
        let theirs = student.pixels[i];
        let (flipped, own) = (
            apart(reference.pixels[j], theirs),
            apart(reference.pixels[i], theirs),
        );
        nearer += usize::from(flipped < own);
        farther += usize::from(flipped > own);
    }
    nearer * 4 >= farther * 5 && nearer * HIDDEN_FLIP >= sample.len()
}

/// [`hidden_flip`]'s least share of the large sample: a pixel in this many.
const HIDDEN_FLIP: usize = 10;

/// Where `moves` only shift the pixels (rows and columns off, the image upside down) of
/// the image `options` render: for a pixel of the image under `moved` (its index),
/// the index of the reference's pixel whose ray it shows, `None` where that ray lies
/// past the window's edge. The world point of pixel i + N is the one row or column
/// offset N gives pixel i (`Camera::new` adds N to i before it divides), so the bytes
/// are the same.
pub(super) fn shifted_from(
    options: &Options,
    moved: &Options,
    moves: &[Variant],
) -> Option<impl Fn(usize) -> Option<usize> + use<>> {
    let width = options.width;
    let Shift { row_from, columns } = shift(options, moved, moves)?;
    Some(move |i: usize| {
        let (r, x) = (i / width, i % width);
        Some(row_from(r)? * width + columns.from(x)?)
    })
}

/// [`shifted_from`] a row at a time: for a row of the image under `moved`, the
/// reference's row whose rays it shows, and for a column the reference's.
struct Shift<R> {
    row_from: R,
    columns: Columns,
}

/// The columns a column offset reads: column x shows the reference's x + N, inside the
/// window from `first` to `end`.
#[derive(Clone, Copy)]
struct Columns {
    offset: i64,
    first: usize,
    end: usize,
}

impl Columns {
    /// Column x reads x + `offset`, in a window `width` wide.
    fn of(offset: i64, width: usize) -> Columns {
        let w = width as i64;
        let first = (-offset).clamp(0, w) as usize;
        let end = (w - offset).clamp(first as i64, w) as usize;
        Columns { offset, first, end }
    }

    /// The reference's column that column `x` shows, `None` past the window's edge.
    fn from(self, x: usize) -> Option<usize> {
        (self.first..self.end)
            .contains(&x)
            .then(|| (x as i64 + self.offset) as usize)
    }
}

/// The [`Shift`] of `moves` ([`shifted_from`]).
fn shift(
    options: &Options,
    moved: &Options,
    moves: &[Variant],
) -> Option<Shift<impl Fn(usize) -> Option<usize> + use<>>> {
    let has = |options: &Options, kind: Kind| options.variants.iter().any(|v| v.kind == kind);
    if !moves.iter().all(|v| SHIFTS.contains(&v.kind)) || has(options, Kind::Jitter) {
        return None;
    }
    let (rows, columns) = offsets(moves);
    let (width, height) = (options.width, options.height);
    // Whether each image is written upside down, once: `Options::row_of` looks.
    let flipped = [has(options, Kind::UpsideDown), has(moved, Kind::UpsideDown)];
    let row_from = move |r: usize| {
        let y = output_row(r, height, flipped[1]) as i64 + rows;
        (0..height as i64)
            .contains(&y)
            .then(|| output_row(y as usize, height, flipped[0]))
    };
    Some(Shift {
        row_from,
        columns: Columns::of(columns, width),
    })
}

/// The rows and the columns the offsets among `variants` move the image by (N of
/// `row-offset=N` and `column-offset=N`; 0 without them).
fn offsets(variants: &[Variant]) -> (i64, i64) {
    let offset = |kind: Kind| {
        (variants.iter())
            .filter(|v| v.kind == kind)
            .map(|v| v.value.unwrap_or(1.0) as i64)
            .sum::<i64>()
    };
    (offset(Kind::RowOffset), offset(Kind::ColumnOffset))
}

/// Whether output pixel i of the image `options` render is one that a row or column
/// offset among their variants leaves uncovered (its ray beyond the window): a program
/// with that mistake writes there what its buffer held, so a difference there is the
/// offset's.
fn uncovered(options: &Options) -> impl Fn(usize) -> bool + use<> {
    let variants: Vec<Variant> = options.variants.iter().collect();
    let (rows, columns) = offsets(&variants);
    let (width, h) = (options.width, options.height as i64);
    // Row r traces y = H-1-r+N: inside the window for r from N to H+N; written upside
    // down, y = r+N, for r from -N to H-N. Column x traces x+N. The rows inside are one
    // run of pixels.
    let flipped = variants.iter().any(|v| v.kind == Kind::UpsideDown);
    let first = if flipped { -rows } else { rows };
    let first_row = first.clamp(0, h);
    let end_row = (h + first).clamp(first_row, h);
    let covered = first_row as usize * width..end_row as usize * width;
    let columns = Columns::of(columns, width);
    let every_column = columns.first == 0 && columns.end == width;
    move |i: usize| !covered.contains(&i) || (!every_column && columns.from(i % width).is_none())
}

/// The pixels of the reference that agree with the student's image within the tolerance
/// when a byte rule (or none) alone applies (pixel i: bit i % 64 of word i / 64), and how
/// many: what every candidate with that byte rule keeps where it traces nothing.
struct Agreeing {
    mask: Vec<u64>,
}

impl Agreeing {
    /// Under `rule`, from the reference's bytes and the steps its paths hold; `differing`
    /// is the reference's own mask of differing pixels, the answer for no rule.
    fn under(
        rule: Option<Kind>,
        rendered: &Reference,
        student: &Image,
        levels: u8,
        (differing, _): (&[u64], usize),
    ) -> Agreeing {
        let pixels = student.pixels.len();
        if rule.is_none() {
            let mask = differing.iter().map(|&word| !word).collect();
            return Agreeing { mask };
        }
        let steps = super::Steps::of(rule);
        let reference = (rendered.paths.chunks(64)).zip(rendered.image.pixels.chunks(64));
        let mut mask = Vec::with_capacity(pixels.div_ceil(64));
        for ((paths, bytes), theirs) in reference.zip(student.pixels.chunks(64)) {
            let mut word = 0u64;
            for (k, ((&paths, &bytes), &theirs)) in paths.iter().zip(bytes).zip(theirs).enumerate()
            {
                word |= u64::from(within(steps.apply(paths, bytes), theirs, levels)) << k;
            }
            mask.push(word);
        }
        Agreeing { mask }
    }

    fn at(&self, i: usize) -> bool {
        is_set(&self.mask, i)
    }
}

/// What scores a candidate exactly: the reference, the student's image, which pixels
/// differ, and the agreement under each byte rule, computed once each when a candidate
/// first needs it.
struct Scorer<'a> {
    scene: &'a Scene,
    options: &'a Options,
    rendered: &'a Reference,
    student: &'a Image,
    levels: u8,
    /// Which pixels differ (pixel i: bit i % 64 of word i / 64), and how many.
    mask: &'a [u64],
    differing: usize,
    /// Pixels that count neither way (empty: none), as [`with_mask`]'s `ignored`.
    ignored: &'a [u64],
    /// The variants the reference was rendered with.
    given: &'a [Variant],
    untouched: [std::cell::OnceCell<Agreeing>; 3],
    /// The last variants whose reach was traced again over the whole image, with the
    /// bytes of the pixels it touches: a move with a mistake and the mistake alone trace
    /// the same pixels under the same rules ([`Scorer::retraced`]).
    retraced: Retraced,
}

/// [`Scorer::retraced`]'s one set of variants, in the order given, and its bytes.
type Retraced = std::cell::RefCell<Option<(Vec<Variant>, std::rc::Rc<Vec<[u8; 3]>>)>>;

impl Scorer<'_> {
    /// What `variants` do to the image, pixel by pixel ([`Counts`]): every pixel they can
    /// change traced again (the whole image when that may be any, [`Reach`]), the others
    /// the reference's (under their byte rule). `None` when they cannot apply together.
    fn counts(&self, variants: &[Variant]) -> Option<Counts> {
        let options = self.options.with_variants(variants).ok()?;
        let was_differing = |i: usize| is_set(self.mask, i);
        let mut counts = Counts::default();
        let ignored = |i: usize| {
            self.ignored
                .get(i / 64)
                .is_some_and(|w| w >> (i % 64) & 1 == 1)
        };
        let uncovered = uncovered(&options);
        let tally = |i: usize, agrees_now: bool| match (was_differing(i), agrees_now) {
            _ if ignored(i) => {}
            // What a program with the offset writes there is its buffer's: the offset
            // explains any difference, and breaks nothing.
            (true, _) if uncovered(i) => counts.fixed += 1,
            _ if uncovered(i) => {}
            (true, true) => counts.fixed += 1,
            (false, false) => counts.broken += 1,
            _ => {}
        };
        self.agreement_under(variants, &options, tally);
        Some(counts)
    }

    /// `each(i, agrees)` for every pixel i in order: whether the image under `variants`
    /// (`options`) agrees with the student's there; for a pixel an offset leaves
    /// uncovered, false. Every pixel they can change traced again (the whole image when
    /// that may be any, [`Reach`]), the others the reference's (under their byte rule);
    /// rows or columns off, the image upside down, the reference's pixels moved.
    fn agreement_under(
        &self,
        variants: &[Variant],
        options: &Options,
        mut each: impl FnMut(usize, bool),
    ) {
        let (scene, rendered) = (self.scene, self.rendered);
        let pixels = rendered.image.pixels.len();
        let agrees = |i: usize, b: [u8; 3]| within(b, self.student.pixels[i], self.levels);
        let uncovered = uncovered(options);
        let reach = match rendered.paths.len() == pixels {
            true => Reach::of(scene, self.given, variants),
            false => None,
        };
        // Rows or columns off, the image upside down: the reference's pixels moved (under
        // the other variants' reach), not a render.
        if reach.is_none()
            && let Some((image, edge)) = self.shifted(variants, options)
        {
            let mut edge = edge.into_iter();
            for (i, b) in image.into_iter().enumerate() {
                match b {
                    Some(b) => each(i, agrees(i, b)),
                    None if uncovered(i) => each(i, false),
                    None => each(i, edge.next().is_some_and(|b| agrees(i, b))),
                }
            }
            return;
        }
        match reach {
            Some(reach) => {
                let rule = reach.byte_rule();
                let untouched = self.untouched[rule_slot(rule)].get_or_init(|| {
                    let mask = (self.mask, self.differing);
                    Agreeing::under(rule, rendered, self.student, self.levels, mask)
                });
                let paths = &rendered.paths;
                let traced: Vec<usize> = match reach.traces() {
                    true => (0..pixels).filter(|&i| reach.touches(paths[i])).collect(),
                    false => Vec::new(),
                };
                // A byte rule alone traces nothing (and sets up no renderer).
                let bytes = match traced.is_empty() {
                    true => Default::default(),
                    false => self.retraced(variants, options, &traced),
                };
                let mut next = traced.iter().zip(bytes.iter().copied()).peekable();
                for i in 0..pixels {
                    match next.peek() {
                        Some(&(&at, b)) if at == i => {
                            each(i, agrees(i, b));
                            next.next();
                        }
                        _ => each(i, untouched.at(i)),
                    }
                }
            }
            None => {
                let image = render::render(scene, options, |_| {});
                for (i, b) in image.pixels.into_iter().enumerate() {
                    each(i, agrees(i, b));
                }
            }
        }
    }
}

impl Scorer<'_> {
    /// The bytes of the pixels `traced` (a reach's, over the whole image) under
    /// `variants` (`options`): rendered, or the last set's where the variants are the
    /// same. A move with a mistake and the mistake alone (the diagnosis counts both)
    /// trace the same pixels under the same rules; one set is kept, an image's bytes at
    /// most.
    fn retraced(
        &self,
        variants: &[Variant],
        options: &Options,
        traced: &[usize],
    ) -> std::rc::Rc<Vec<[u8; 3]>> {
        let mut last = self.retraced.borrow_mut();
        if let Some((held, bytes)) = last.as_ref()
            && held == variants
            && bytes.len() == traced.len()
        {
            return bytes.clone();
        }
        let bytes = std::rc::Rc::new(super::render_pixels(self.scene, options, traced));
        *last = Some((variants.to_vec(), bytes.clone()));
        bytes
    }
}

impl Scorer<'_> {
    /// The pixels that `first` leaves differing, and those that agree under it (past an
    /// offset's uncovered edge, neither): each a bit a pixel (pixel i: bit i % 64 of word
    /// i / 64) and how many; `None` where it does not apply. A move of the pixels (a row
    /// off, upside down) moves the reference's; another is traced where it reaches.
    fn left(&self, first: &[Variant]) -> Option<[(Vec<u64>, usize); 2]> {
        let options = self.options.with_variants(first).ok()?;
        let uncovered = uncovered(&options);
        let words = self.rendered.image.pixels.len().div_ceil(64);
        let [mut left, mut kept] = [(vec![0u64; words], 0), (vec![0u64; words], 0)];
        self.agreement_under(first, &options, |i, agrees_now| {
            if uncovered(i) {
                return;
            }
            let (mask, count) = if agrees_now { &mut kept } else { &mut left };
            mask[i / 64] |= 1 << (i % 64);
            *count += 1;
        });
        Some([left, kept])
    }

    /// Of `partners` (and the variants of one record that the rays of the pixels `left`
    /// meet, traced under `first`), those that with `first` are estimated to agree best,
    /// best first (among equals, in the candidates' order): on even samples of the
    /// pixels `first` leaves differing and of those that agree under it (`left`), each
    /// candidate on the small ones and the [`SHORTLIST`] best again on the large. Each
    /// with the agreement estimated and the pixels of the large sample it fixes.
    fn best_partners(
        &self,
        first: &[Variant],
        mut partners: Vec<Variant>,
        [(left, left_count), (kept, kept_count)]: &[(Vec<u64>, usize); 2],
    ) -> Vec<(Variant, (f64, Vec<usize>))> {
        let (scene, options) = (self.scene, self.options);
        let Ok(moved) = options.with_variants(first) else {
            return Vec::new();
        };
        let pixels = self.rendered.image.pixels.len();
        let samples = SAMPLE.map(|n| {
            let every = |mask: &[u64], count: usize| {
                every_nth(mask, pixels, true, count.div_ceil(n).max(1))
            };
            [every(left, *left_count), every(kept, *kept_count)]
        });
        if *left_count == 0 {
            return Vec::new();
        }
        for v in scoped(scene, &super::involved(scene, &moved, &samples[1][0])) {
            if !partners.contains(&v) && may_change(scene, options, &v) {
                partners.push(v);
            }
        }
        let agrees = |i: usize, b: [u8; 3]| within(b, self.student.pixels[i], self.levels);
        let share = |n: usize, of: &[usize]| n as f64 / of.len().max(1) as f64;
        let total = pixels.max(1) as f64;
        // The agreement estimated on sample k, and the pixels it fixes there.
        let estimate = |k: usize, partner: Variant| -> Option<(f64, Vec<usize>)> {
            let [sample_left, sample_kept] = &samples[k];
            let both = moved.with_variant(partner).ok()?;
            let sample: Vec<usize> = sample_left.iter().chain(sample_kept).copied().collect();
            let bytes = super::render_pixels(scene, &both, &sample);
            let (on_left, on_kept) = bytes.split_at(sample_left.len());
            let fixed: Vec<usize> = (sample_left.iter().zip(on_left))
                .filter(|&(&i, &b)| agrees(i, b))
                .map(|(&i, _)| i)
                .collect();
            let still = (sample_kept.iter().zip(on_kept))
                .filter(|&(&i, &b)| agrees(i, b))
                .count();
            // The pixels estimated to differ under both (an offset's uncovered edge, none).
            let differing = *left_count as f64 * (1.0 - share(fixed.len(), sample_left))
                + *kept_count as f64 * (1.0 - share(still, sample_kept));
            (!fixed.is_empty()).then_some(((total - differing) / total, fixed))
        };
        // A partner's epsilons reach 1: the few pixels a move leaves of an epsilon of 0.3
        // are lit by none of the first values alone (0.1 and below), and by 1.
        let epsilon_one = Variant {
            value: Some(1.0),
            ..Variant::of(Kind::ShadowEpsilon)
        };
        if !partners.contains(&epsilon_one) && may_change(scene, options, &epsilon_one) {
            partners.push(epsilon_one);
            // And the epsilon the blockers of the large samples' pixels suggest under
            // `first`, as alone, first of its kind (examples/spheres.txt a row off with
            // an epsilon of 2 was told no-shadows: 1 lights some of its pixels, the
            // values near it stop at 1, and 3, estimated on the whole image, ties with
            // 2 on the samples).
            let [sample_left, sample_kept] = &samples[1];
            let sample = [&sample_left[..], sample_kept].concat();
            let split = (&sample[..], sample_left.len());
            let counts = (*left_count, *kept_count);
            if let Some(epsilon) = estimate_epsilon(scene, &moved, split, counts) {
                partners.retain(|v| *v != epsilon);
                let kind = |v: &Variant| v.kind == Kind::ShadowEpsilon;
                let at = partners.iter().position(kind).unwrap_or(partners.len());
                partners.insert(at, epsilon);
            }
        }
        let mut first_round: Vec<(Variant, f64)> = (partners.iter())
            .filter_map(|&partner| Some((partner, estimate(0, partner)?.0)))
            .collect();
        // A continuous partner at the round values near the best of its first ones, as
        // alone (a shadow epsilon of 0.3 after a move, which 1 explains with others).
        for kind in CONTINUOUS {
            let of_kind = |v: &Variant| v.kind == kind && v.line.is_none();
            let tried: Vec<(f64, f64)> = (first_round.iter())
                .filter(|(v, _)| of_kind(v))
                .filter_map(|(v, agreement)| Some((v.value?, *agreement)))
                .collect();
            let values = (partners.iter().filter(|v| of_kind(v)))
                .filter_map(|v| v.value)
                .collect();
            let near = values_near(kind, &tried, values).into_iter();
            first_round.extend(
                near.filter(|v| !partners.contains(v))
                    .filter_map(|partner| Some((partner, estimate(0, partner)?.0))),
            );
        }
        // Best first; a stable sort keeps the candidates' order among equals.
        first_round.sort_by(|a, b| b.1.total_cmp(&a.1));
        first_round.truncate(SHORTLIST);
        let mut ranked: Vec<(Variant, (f64, Vec<usize>))> = (first_round.into_iter())
            .filter_map(|(partner, _)| Some((partner, estimate(1, partner)?)))
            .collect();
        // Of stops estimated alike, the later first: it leaves out fewer records, so it
        // makes no more pixels differ.
        let line = |v: &Variant| (v.kind == Kind::StoppedAt).then_some(v.line).flatten();
        ranked.sort_by(|a, b| (b.1.0.total_cmp(&a.1.0)).then(line(&b.0).cmp(&line(&a.0))));
        ranked
    }

    /// The image under `variants` (at `options`) where those among them that move pixels
    /// only shift them (rows and columns off, upside down) and the others reach few
    /// pixels: each pixel the reference's from where its ray comes, under the others
    /// ([`reached`]); `None` for a pixel whose ray lies past the window's edge, with, in
    /// order, the bytes of those among them no offset leaves uncovered (rendered).
    /// `None` where the variants are not of that kind.
    #[allow(clippy::type_complexity)]
    fn shifted(
        &self,
        variants: &[Variant],
        options: &Options,
    ) -> Option<(Vec<Option<[u8; 3]>>, Vec<[u8; 3]>)> {
        let (scene, rendered) = (self.scene, self.rendered);
        let pixels = rendered.image.pixels.len();
        let shifts = |v: &&Variant| SHIFTS.contains(&v.kind);
        let moves: Vec<Variant> = variants.iter().filter(shifts).copied().collect();
        let rest: Vec<Variant> = variants.iter().filter(|v| !shifts(v)).copied().collect();
        if moves.is_empty() || rendered.paths.len() != pixels {
            return None;
        }
        let reach = Reach::of(scene, self.given, &rest)?;
        let Shift { row_from, columns } = shift(self.options, options, &moves)?;
        let under_rest = self.options.with_variants(&rest).ok()?;
        // The reference's pixels under the other variants, as `reached` gives them: stepped
        // under their rule of the bytes, and traced again where they reach (the bytes the
        // mistake alone had, or will have: `Scorer::retraced`).
        let (paths, bytes) = (&rendered.paths, &rendered.image.pixels);
        let mut moved: Vec<[u8; 3]> = (0..pixels)
            .map(|j| reach.untouched(paths[j], bytes[j]))
            .collect();
        if reach.traces() {
            let touched: Vec<usize> = (0..pixels).filter(|&i| reach.touches(paths[i])).collect();
            let retraced = self.retraced(&rest, &under_rest, &touched);
            for (&j, &b) in touched.iter().zip(retraced.iter()) {
                moved[j] = b;
            }
        }
        let width = options.width;
        let mut image: Vec<Option<[u8; 3]>> = Vec::with_capacity(pixels);
        for r in 0..options.height {
            match row_from(r) {
                Some(row) => {
                    let at = |x: usize| columns.from(x).map(|x| moved[row * width + x]);
                    image.extend((0..width).map(at));
                }
                None => image.extend(std::iter::repeat_n(None, width)),
            }
        }
        let uncovered = uncovered(options);
        let edge: Vec<usize> = (0..pixels)
            .filter(|&i| image[i].is_none() && !uncovered(i))
            .collect();
        Some((image, super::render_pixels(scene, options, &edge)))
    }
}

/// The variants that move the image's pixels without changing them: what a pixel shows
/// is the reference's pixel from elsewhere ([`shifted_from`]).
pub(super) const SHIFTS: [Kind; 3] = [Kind::RowOffset, Kind::ColumnOffset, Kind::UpsideDown];

/// The causes `variants` state: the moves they begin with as one (an image upside down
/// and a row off is one loop that writes the rows), then each other variant alone.
pub(super) fn units(variants: &[Variant]) -> Vec<&[Variant]> {
    let moves = (variants.iter())
        .take_while(|v| SHIFTS.contains(&v.kind))
        .count();
    let (moves, others) = variants.split_at(moves);
    let moves = Some(moves).filter(|m| !m.is_empty());
    moves.into_iter().chain(others.chunks(1)).collect()
}

/// The place of a byte rule's [`Agreeing`] among the three: none, round-bytes, scale-256.
fn rule_slot(rule: Option<Kind>) -> usize {
    match rule {
        Some(Kind::RoundBytes) => 1,
        Some(Kind::Scale256) => 2,
        _ => 0,
    }
}

/// The pixels whose bit in `mask` is `set` (of the first `pixels`), the first and then
/// every `every`-th: `(0..pixels).filter(..).step_by(every)`, a word at a time.
fn every_nth(mask: &[u64], pixels: usize, set: bool, every: usize) -> Vec<usize> {
    let mut picked = Vec::new();
    // How many more of the pixels to pass before the next is picked.
    let mut pass = 0;
    for (w, &word) in mask.iter().enumerate() {
        let mut bits = if set { word } else { !word };
        let valid = pixels.saturating_sub(w * 64);
        if valid < 64 {
            bits &= (1u64 << valid) - 1;
        }
        loop {
            let count = bits.count_ones() as usize;
            if pass >= count {
                pass -= count;
                break;
            }
            for _ in 0..pass {
                bits &= bits - 1;
            }
            picked.push(w * 64 + bits.trailing_zeros() as usize);
            bits &= bits - 1;
            pass = every - 1;
        }
    }
    picked
}

/// "cone (line 34)" for the record a scoped variant among `variants` names.
fn subject(scene: &Scene, variants: &[Variant]) -> Option<String> {
    let line = variants.iter().find_map(|v| v.line)?;
    let object = scene.objects.iter().find(|o| o.line == line);
    let kind = object.map_or("light", |o| o.kind());
    Some(format!("{kind} (line {line})"))
}

/// Whether `variant` can change a pixel of the scene's image under `options`: only where
/// the rule it replaces is consulted. The lights' rules need a light that the stage
/// lights, the mirror's an object that reflects (the one it is scoped to, or any) under a
/// stage that reflects, a normal's either (or the image of the normals); a variant of
/// some kinds of object (cones, tiled planes, ...) an object of those kinds. Those that
/// cannot are not tried: their agreement is the reference's.
fn may_change(scene: &Scene, options: &Options, variant: &Variant) -> bool {
    let traced = options.show.is_none();
    let lit = traced && options.stage.lights() && !scene.lights.is_empty();
    let object = (variant.line).and_then(|line| scene.objects.iter().find(|o| o.line == line));
    let mirrors = traced
        && options.stage.reflects()
        && match object {
            Some(object) => object.reflects(),
            None => scene.objects.iter().any(Object::reflects),
        };
    match variant.row().needs {
        Needs::Light => lit,
        Needs::Mirror => mirrors,
        Needs::LightOrMirror => lit || mirrors,
        Needs::Shading => lit || mirrors || options.show == Some(render::Show::Normals),
        Needs::Kinds => match (variant.row().scope, object) {
            (Scope::ImageOrObject(kinds), None) => {
                scene.objects.iter().any(|o| kinds.admit(&o.shape))
            }
            _ => true,
        },
    }
}

/// The values of the continuous and whole-number variants tried besides their first
/// (spec §7.5): rows and columns off by up to three either way, a few z tolerances, far
/// clips and shadow epsilons (round values, as students write them).
fn other_values() -> Vec<Variant> {
    let with = |kind: Kind, value: f64| Variant {
        value: Some(value),
        ..Variant::of(kind)
    };
    let mut out = Vec::new();
    for n in [-3.0, -2.0, -1.0, 2.0, 3.0] {
        out.push(with(Kind::RowOffset, n));
        out.push(with(Kind::ColumnOffset, n));
    }
    out.extend([0.001, 0.05, 0.1, 0.2, 0.5, 1.0].map(|e| with(Kind::ZTolerance, e)));
    out.extend([10.0, 20.0, 50.0, 100.0].map(|d| with(Kind::FarClip, d)));
    out.extend([1e-4, 1e-3, 0.01, 0.1].map(|e| with(Kind::ShadowEpsilon, e)));
    out
}

/// The round numbers strictly between `low` and `high` (0 < low < high), the roundest
/// first: the multiples of the largest power of ten that fits, then of its half, then
/// of a tenth of it; at most [`ROUND_VALUES`]. Each is a decimal as written (0.15, not
/// 0.15000000000000002).
fn round_values_between(low: f64, high: f64) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::new();
    let exponent = (high - low).log10().floor() as i32;
    for (e, half) in [(exponent, false), (exponent, true), (exponent - 1, false)] {
        // k / 10^-e (or k * 10^e): a division by a whole power of ten rounds once.
        let (scale, divide) = (10f64.powi(e.abs()), e < 0);
        let step_in_units = if half { 0.5 } else { 1.0 };
        let at = |k: f64| match divide {
            true => k * step_in_units / scale,
            false => k * step_in_units * scale,
        };
        let mut k = (if divide { low * scale } else { low / scale } / step_in_units).floor();
        // high - low is under 10 of the largest step and under 100 of the smallest, so
        // some hundred steps reach `high`; the bound holds besides where `low` is so large
        // against the step that k + 1 is k (a range one ulp wide).
        for _ in 0..STEPS_BETWEEN {
            if out.len() >= ROUND_VALUES {
                break;
            }
            let value = at(k);
            if value >= high {
                break;
            }
            if value > low && !out.contains(&value) {
                out.push(value);
            }
            k += 1.0;
        }
    }
    out
}

/// The values of a continuous parameter of `kind` to try next, given those `tried` (each
/// with its agreement) among `values` (those tried so far): none where none was tried,
/// else the round values between the neighbours of those that tie with the best (up to
/// the next step past the last), the roundest first.
fn values_near(kind: Kind, tried: &[(f64, f64)], mut values: Vec<f64>) -> Vec<Variant> {
    let Some(best) = tried.iter().map(|t| t.1).reduce(f64::max) else {
        return Vec::new();
    };
    let tied = || tried.iter().filter(|t| t.1 == best).map(|t| t.0);
    let (first, last) = (tied().fold(f64::MAX, f64::min), tied().fold(0.0, f64::max));
    values.sort_by(f64::total_cmp);
    let below = values.iter().rev().find(|&&v| v < first).copied();
    let above = values.iter().find(|&&v| v > last).copied();
    // Past the values tried: as far as the next of them would lie (the epsilons go by
    // tens).
    let step = if kind == Kind::ShadowEpsilon {
        10.0
    } else {
        2.0
    };
    let (low, high) = (below.unwrap_or(first / step), above.unwrap_or(last * step));
    (round_values_between(low, high).into_iter())
        .map(|value| Variant {
            value: Some(value),
            ..Variant::of(kind)
        })
        .collect()
}

/// How many steps [`round_values_between`] takes at most, of each size.
const STEPS_BETWEEN: usize = 128;

/// How many round values a continuous parameter is tried at between two of its first.
const ROUND_VALUES: usize = 32;

/// How many records' lines a reader that stopped is tried at.
const STOPS: usize = 32;

/// A reader that stopped (stopped-at@LINE, spec §7.5): at the second record's line and
/// on, up to [`STOPS`] of them spread over the file (at every one in a scene of few).
fn stopped(scene: &Scene) -> Vec<Variant> {
    let lines = stops(scene);
    let every = lines.len().div_ceil(STOPS).max(1);
    (lines.iter().step_by(every))
        .map(|&line| Variant::of(Kind::StoppedAt).at(line))
        .collect()
}

/// The lines a reader may have stopped at: every record's but the first, in order.
fn stops(scene: &Scene) -> Vec<usize> {
    let mut lines: Vec<usize> = (scene.objects.iter().map(|o| o.line))
        .chain(scene.lights.iter().map(|l| l.line))
        .collect();
    lines.sort_unstable();
    lines.split_off(1.min(lines.len()))
}

/// The stops [`stopped`] skipped around `line`: every record's line between the tried
/// stops before and after it.
fn stopped_near(scene: &Scene, line: usize) -> Vec<Variant> {
    let lines = stops(scene);
    let every = lines.len().div_ceil(STOPS).max(1);
    let at = lines.partition_point(|&l| l < line);
    let range = at.saturating_sub(every)..(at + every).min(lines.len());
    (lines[range].iter())
        .map(|&line| Variant::of(Kind::StoppedAt).at(line))
        .collect()
}

/// The edits of one record on the objects and the lights most involved in the sampled
/// differing pixels' paths, most involved first.
fn scoped(scene: &Scene, paths: &[super::Involved]) -> Vec<Variant> {
    let mut objects = vec![0usize; scene.objects.len()];
    let mut lights = vec![0usize; scene.lights.len()];
    for path in paths {
        let blockers = path.blockers.iter();
        for object in distinct(
            path.hits
                .iter()
                .copied()
                .chain(blockers.clone().map(|b| b.0)),
        ) {
            objects[object] += 1;
        }
        for light in distinct(path.lit_by.iter().copied().chain(blockers.map(|b| b.1))) {
            lights[light] += 1;
        }
    }
    let most = |counts: &[usize]| -> Vec<usize> {
        let mut order: Vec<usize> = (0..counts.len()).filter(|&i| counts[i] > 0).collect();
        order.sort_by_key(|&i| std::cmp::Reverse(counts[i]));
        order.truncate(SUBJECTS);
        order
    };
    let mut edits = Vec::new();
    for object in most(&objects) {
        let object = &scene.objects[object];
        edits.extend(edits_of(Some(&object.shape), object.line));
    }
    for light in most(&lights) {
        edits.extend(edits_of(None, scene.lights[light].line));
    }
    edits
}

/// The edits of the record on `line`: an object of this shape (cone-scale only for a
/// cone, ...), or a light (`None`).
fn edits_of(shape: Option<&Shape>, line: usize) -> impl Iterator<Item = Variant> + '_ {
    let fits = move |row: &&Row| match (row.scope, shape) {
        (Scope::ImageOrObject(kinds) | Scope::Object(kinds), Some(shape)) => kinds.admit(shape),
        (Scope::ImageOrLight | Scope::Light, None) => true,
        _ => false,
    };
    VARIANTS
        .iter()
        .filter(fits)
        .map(move |row| Variant::of(row.kind).at(line))
}

/// The indices `of` yields, each once: a path's objects or lights, a few.
fn distinct(of: impl Iterator<Item = usize>) -> Vec<usize> {
    let mut all: Vec<usize> = of.collect();
    all.sort_unstable();
    all.dedup();
    all
}

/// The object most involved in the sampled differing pixels' paths (the first of
/// `paths`; the second, the agreeing ones'), and how: each path counts once for an
/// object, as the camera ray's hit first, else as a shadow's blocker, else as a mirror
/// ray's hit. `moved` is how each sampled differing pixel's channels differ, and
/// `differing_where_hit(object)` the share of the pixels whose rays hit an object that
/// differ.
fn focus(
    scene: &Scene,
    [paths, agreeing]: [&[super::Involved]; 2],
    moved: &[[i16; 3]],
    differing_where_hit: &dyn Fn(usize) -> f64,
) -> Option<Focus> {
    // Per object: the paths that involve it, then by the camera, a shadow, a mirror.
    let mut per_object = vec![[0usize; 4]; scene.objects.len()];
    for path in paths {
        let camera = path.hits.first().copied();
        let blockers: Vec<usize> = path.blockers.iter().map(|b| b.0).collect();
        for object in distinct(path.hits.iter().copied().chain(blockers.iter().copied())) {
            let how = if Some(object) == camera {
                1
            } else if blockers.contains(&object) {
                2
            } else {
                3
            };
            per_object[object][0] += 1;
            per_object[object][how] += 1;
        }
    }
    let index = (0..per_object.len()).max_by_key(|&i| (per_object[i][0], std::cmp::Reverse(i)))?;
    let [n, camera, shadow, mirror] = per_object[index];
    if n == 0 {
        return None;
    }
    let share = |k: usize| k as f64 / n as f64;
    let light = light_focus(scene, paths, agreeing);
    let hit = paths
        .iter()
        .filter(|p| p.hits.first() == Some(&index))
        .count();
    // Another colour moves each channel one way on every pixel; the object moved makes
    // one side lighter and the other darker.
    let on_it = (paths.iter().zip(moved)).filter(|(p, _)| p.hits.first() == Some(&index));
    let mut ways = [[0usize; 2]; 3];
    for (_, moved) in on_it {
        for c in 0..3 {
            match moved[c].signum() {
                1 => ways[c][0] += 1,
                -1 => ways[c][1] += 1,
                _ => {}
            }
        }
    }
    let one_way = ways
        .iter()
        .all(|&[up, down]| up.min(down) as f64 <= (1.0 - MATERIAL_ONE_WAY) * (up + down) as f64);
    let material = (light.is_none() && hit as f64 >= MATERIAL_CAMERA * paths.len() as f64)
        .then(|| differing_where_hit(index))
        .filter(|&differ| differ >= MATERIAL_DIFFERING && one_way);
    Some(Focus {
        object: object_name(scene, index),
        index,
        share: n as f64 / paths.len().max(1) as f64,
        camera: share(camera),
        shadow: share(shadow),
        mirror: share(mirror),
        light,
        material,
    })
}

/// The light that lights at least [`LIGHT_DIFFERING`] of the differing pixels' paths and
/// at most [`LIGHT_AGREEING`] of the agreeing ones', the one whose two shares differ most.
fn light_focus(
    scene: &Scene,
    differing: &[super::Involved],
    agreeing: &[super::Involved],
) -> Option<LightFocus> {
    let lit = |paths: &[super::Involved], light: usize| {
        let n = paths.iter().filter(|p| p.lit_by.contains(&light)).count();
        n as f64 / paths.len().max(1) as f64
    };
    (0..scene.lights.len())
        .map(|k| (k, lit(differing, k), lit(agreeing, k)))
        .filter(|&(_, d, a)| d >= LIGHT_DIFFERING && a <= LIGHT_AGREEING)
        .max_by(|x, y| (x.1 - x.2).total_cmp(&(y.1 - y.2)))
        .map(|(index, differing, agreeing)| LightFocus {
            light: super::light_name(scene, index),
            index,
            differing,
            agreeing,
        })
}

/// The MAX_DIST D under which the scene's image agrees best with `student`, the range of
/// D that gives that same image, the agreement, and a pixel (output index) that differs
/// under `options`' MAX_DIST and agrees under D; `None` if no D up to [`PROBE_LIMIT`]
/// changes the image. D is the roundest number in the range (70 rather than 66.3).
pub fn estimate_max_dist(
    scene: &Scene,
    options: &Options,
    student: &Image,
    levels: u8,
) -> Option<(f64, [f64; 2], f64, Option<usize>)> {
    // MAX_DIST cuts mirror paths only (spec §4.2 step 1 never stops the camera ray): a
    // scene without a mirror has one image under every D.
    if !scene.objects.iter().any(Object::reflects) {
        return None;
    }
    let probe = probe(options);
    let (state, changes) = super::path_agreement(scene, &probe, |pixel, bytes| {
        within(bytes, student.pixels[pixel], levels)
    });
    let (d, range, best) = best_max_dist(&state, &changes, |_| 1.0, options.max_dist)?;
    // Each pixel's agreement under a MAX_DIST: the changes up to it replayed.
    let under = |limit: f64| {
        let mut state = state.clone();
        for change in changes.iter().take_while(|c| c.start <= limit) {
            state[change.pixel as usize] = change.agrees;
        }
        state
    };
    let (now, then) = (under(options.max_dist), under(d));
    let pixel = (0..state.len()).find(|&i| !now[i] && then[i]);
    Some((d, range, best / student.pixels.len().max(1) as f64, pixel))
}

/// The shadow epsilon (spec §7.5) to try where none of the first did better than the
/// image as it is: the roundest value of the range of ε that would make the most of
/// `sample`'s pixels agree (its differing ones, then from `split` its agreeing ones;
/// `counts` of each in the image), as far as the farthest blockers of their shadow rays
/// tell. A differing pixel is taken to agree, and an agreeing one to differ, from the ε
/// at which its first shadow ray is blocked no more; the render of the value says
/// whether it does. None where no ε does better than none, or the range holds no round
/// value.
fn estimate_epsilon(
    scene: &Scene,
    options: &Options,
    (sample, split): (&[usize], usize),
    (differing, agreeing): (usize, usize),
) -> Option<Variant> {
    let at = super::unblocked_at(scene, options, sample);
    let mut changes: Vec<super::PathChange> = (at.iter().enumerate())
        .filter_map(|(i, t)| {
            Some(super::PathChange {
                start: (*t)?,
                pixel: i as u32,
                agrees: i < split,
            })
        })
        .collect();
    super::by_distance(&mut changes);
    let state: Vec<bool> = (0..sample.len()).map(|i| i >= split).collect();
    let weight = sample_weight((sample, split), (differing, agreeing));
    let (epsilon, [low, high], _) = best_max_dist(&state, &changes, weight, 0.0)?;
    // A student writes a round ε: a range too narrow to hold one is a coincidence of a
    // few pixels.
    if roundest(low, high).1 == 0.0 {
        return None;
    }
    Some(Variant {
        value: Some(epsilon),
        ..Variant::of(Kind::ShadowEpsilon)
    })
}

/// The weight of the k-th pixel of a sample whose first `split` pixels differ: the
/// share of the image's pixels of its kind (`differing`, `agreeing`) that it stands for.
fn sample_weight(
    (sample, split): (&[usize], usize),
    (differing, agreeing): (usize, usize),
) -> impl Fn(usize) -> f64 + use<> {
    let share = |count: usize, of: usize| count as f64 / of.max(1) as f64;
    let weights = [
        share(differing, split),
        share(agreeing, sample.len() - split),
    ];
    move |k| weights[usize::from(k >= split)]
}

/// The options [`estimate_max_dist`] renders with: MAX_DIST at [`PROBE_LIMIT`] or more.
fn probe(options: &Options) -> Options {
    Options {
        max_dist: PROBE_LIMIT.max(options.max_dist),
        ..*options
    }
}

/// Of the pixels whose bytes agree under the smallest MAX_DIST (`state`) and change as D
/// grows (`changes`, by D), each counted with its `weight`: the roundest D that agrees
/// best, its range, and that agreement (the weights' sum); `None` where none agrees
/// better than the `current` D. The same sweep serves a shadow epsilon, whose changes
/// lie where ε passes a pixel's blockers ([`estimate_epsilon`]).
fn best_max_dist(
    state: &[bool],
    changes: &[super::PathChange],
    weight: impl Fn(usize) -> f64,
    current: f64,
) -> Option<(f64, [f64; 2], f64)> {
    let mut state = state.to_vec();
    let mut agreeing: f64 = (state.iter().enumerate())
        .filter(|&(_, &s)| s)
        .map(|(i, _)| weight(i))
        .sum();
    // Agreement on each interval [start, next start) of D.
    let mut intervals: Vec<(f64, f64)> = vec![(0.0, agreeing)];
    for change in changes {
        let pixel = change.pixel as usize;
        let w = weight(pixel);
        agreeing += f64::from(u8::from(change.agrees)) * w - f64::from(u8::from(state[pixel])) * w;
        state[pixel] = change.agrees;
        match intervals.last_mut() {
            Some(last) if last.0 == change.start => last.1 = agreeing,
            _ => intervals.push((change.start, agreeing)),
        }
    }
    let limit = PROBE_LIMIT.max(current);
    let end = |i: usize| intervals.get(i + 1).map_or(limit, |next| next.0);
    let at = intervals.iter().rposition(|&(start, _)| start <= current)?;
    let best = intervals
        .iter()
        .map(|&(_, count)| count)
        .fold(f64::MIN, f64::max);
    if best <= intervals[at].1 {
        return None;
    }
    // Among the ranges that agree best, the one with the roundest D (the student wrote
    // 70, not 68.917), then the smallest. The last range holds its end: the probe's
    // MAX_DIST itself gives its image (a student's 1000 is 1000, not 997).
    let last = intervals.len() - 1;
    let roundest_in = |i: usize, low: f64| match i == last {
        true => roundest(low, end(i).next_up()),
        false => roundest(low, end(i)),
    };
    let (d, range) = (intervals.iter().enumerate())
        .filter(|&(_, &(_, count))| count == best)
        .map(|(i, &(low, _))| (roundest_in(i, low), [low, end(i)]))
        .max_by(|((d1, step1), _), ((d2, step2), _)| step1.total_cmp(step2).then(d2.total_cmp(d1)))
        .map(|((d, _), range)| (d, range))?;
    Some((d, range, best))
}

/// The roundest number D with low <= D < high and D > 0, and its roundness: D is a
/// multiple of the largest step (…, 100, 50, 10, 5, 1, 0.5, 0.1, …) that is at most half
/// of `low` (or at most `high` when `low` is 0) and has a multiple in the range.
pub fn roundest(low: f64, high: f64) -> (f64, f64) {
    let scale = if low > 0.0 { low / 2.0 } else { high };
    let mut exponent = scale.log10().floor() as i32 + 1;
    for _ in 0..40 {
        for half in [false, true] {
            // A step below 1 as the division by a whole number it is (0.1 as 1 / 10), so
            // that its multiples are the decimals written (0.6, not 0.6000000000000001).
            let (whole, per) = match exponent < 0 {
                true => (1.0, 10f64.powi(-exponent)),
                false => (10f64.powi(exponent), 1.0),
            };
            let (whole, per) = match half {
                true if exponent > 0 => (whole / 2.0, per),
                true => (whole, per * 2.0),
                false => (whole, per),
            };
            let s = whole / per;
            if s <= scale {
                let k = (low * per / whole).ceil().max(1.0);
                let multiple = k * whole / per;
                if multiple < high {
                    return (multiple, s);
                }
            }
        }
        exponent -= 1;
    }
    (if low > 0.0 { low } else { high / 2.0 }, 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    /// Every example scene, and the course's where they are beside the project.
    fn scenes() -> Vec<(String, Scene)> {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let mut paths = Vec::new();
        for dir in [root.join("examples"), root.join("../shared/course-scenes")] {
            let Ok(entries) = std::fs::read_dir(dir) else {
                continue;
            };
            paths.extend(entries.flatten().map(|e| e.path()));
        }
        paths.retain(|p| p.extension().is_some_and(|e| e == "txt"));
        paths.sort();
        // The examples' textures are named from the project's folder, where tests run.
        let load = |path: &Path| {
            let text = std::fs::read_to_string(path).unwrap();
            (path.display().to_string(), crate::load(&text).unwrap())
        };
        let scenes: Vec<_> = paths.iter().map(|p| load(p)).collect();
        assert!(scenes.len() >= 20, "the examples are found");
        scenes
    }

    #[test]
    fn a_variant_not_tried_renders_the_reference_s_image() {
        // What `may_change` rules out must change no pixel: checked by rendering, on
        // every scene, for every variant and every edit of every record, at the stage
        // that draws everything and at the ambient one.
        for (name, scene) in scenes() {
            let mut variants: Vec<Variant> = Variant::tried().collect();
            for object in &scene.objects {
                variants.extend(edits_of(Some(&object.shape), object.line));
            }
            for light in &scene.lights {
                variants.extend(edits_of(None, light.line));
            }
            for stage in [render::Stage::Full, render::Stage::Ambient] {
                let options = Options {
                    stage,
                    ..Options::new(40, 30)
                };
                let reference = render::render(&scene, &options, |_| {});
                for variant in variants.iter().filter(|v| !may_change(&scene, &options, v)) {
                    let Ok(with) = options.with_variant(*variant) else {
                        continue;
                    };
                    let image = render::render(&scene, &with, |_| {});
                    assert_eq!(image, reference, "{name} {stage:?} {}", variant.id());
                }
            }
        }
    }

    #[test]
    fn an_exact_agreement_is_the_whole_render_s() {
        // A student's image with two mistakes; each candidate's exact agreement (traced
        // again where it can change, the reference's bytes elsewhere) against the count
        // over the whole image rendered with it.
        for (name, scene) in scenes().into_iter().filter(|(_, s)| !s.objects.is_empty()) {
            let options = Options::new(48, 36);
            let first = scene.objects[0].line;
            let mistakes = [
                Variant::parse(&format!("hidden@{first}")).unwrap(),
                Variant::of(Kind::Scale256),
            ];
            let student_options = mistakes
                .iter()
                .fold(options, |o, &v| o.with_variant(v).unwrap());
            let student = render::render(&scene, &student_options, |_| {});
            let rendered = crate::compare::reference_at(&scene, &options, 1e-7, true);
            let (mask, count) = super::super::differing(&rendered.image, &student, 0);
            let scorer = Scorer {
                scene: &scene,
                options: &options,
                rendered: &rendered,
                student: &student,
                levels: 0,
                mask: &mask,
                differing: count,
                ignored: &[],
                given: &[],
                untouched: Default::default(),
                retraced: Default::default(),
            };
            let mut candidates = vec![
                vec![Variant::of(Kind::RoundBytes)],
                vec![Variant::of(Kind::Scale256)],
            ];
            for edit in edits_of(Some(&scene.objects[0].shape), first) {
                candidates.push(vec![edit]);
                candidates.push(vec![Variant::of(Kind::Scale256), edit]);
                candidates.push(vec![Variant::of(Kind::RoundBytes), edit]);
            }
            let pixels = student.pixels.len();
            for variants in candidates {
                let Ok(with) = options.with_variants(&variants) else {
                    continue;
                };
                if Reach::of(&scene, &[], &variants).is_none() {
                    continue;
                }
                let counts = scorer.counts(&variants).unwrap();
                let exact = pixels - count + counts.fixed - counts.broken;
                // The whole image rendered with the candidate, set against the reference's
                // pixel by pixel: the same counts.
                let whole = render::render(&scene, &with, |_| {});
                let expected = (whole.pixels.iter().zip(&student.pixels))
                    .filter(|(a, b)| a == b)
                    .count();
                let fixed = (0..pixels)
                    .filter(|&i| rendered.image.pixels[i] != student.pixels[i])
                    .filter(|&i| whole.pixels[i] == student.pixels[i])
                    .count();
                let ids: Vec<String> = variants.iter().map(|v| v.id()).collect();
                assert_eq!(exact, expected, "{name} {}", ids.join(","));
                assert_eq!(counts.fixed, fixed, "{name} {}", ids.join(","));
            }
        }
    }

    #[test]
    fn a_max_dist_whose_range_reaches_the_probe_s_limit_may_be_the_limit() {
        // One pixel agrees once D reaches 950, and so on up to the probe's MAX_DIST,
        // whose image it is too: D lies in [950, 1000], and 1000 is its roundest value
        // (were the range open at its end, 950 would be).
        let change = super::super::PathChange {
            start: 950.0,
            pixel: 0,
            agrees: true,
        };
        let found = best_max_dist(&[false], &[change], |_| 1.0, 32.0);
        assert_eq!(found, Some((PROBE_LIMIT, [950.0, PROBE_LIMIT], 1.0)));
        // A range that ends before the limit keeps its end out: [950, 990) gives 950.
        let back = super::super::PathChange {
            start: 990.0,
            agrees: false,
            ..change
        };
        let found = best_max_dist(&[false], &[change, back], |_| 1.0, 32.0);
        assert_eq!(found, Some((950.0, [950.0, 990.0], 1.0)));
    }

    #[test]
    fn round_values_come_roundest_first_and_as_written() {
        // Between 20 and 50: the tens, the fives, then the ones.
        let values = round_values_between(20.0, 50.0);
        assert_eq!(values[..5], [30.0, 40.0, 25.0, 35.0, 45.0]);
        assert_eq!(values[5..8], [21.0, 22.0, 23.0]);
        assert_eq!(values.len(), 2 + 3 + 24);
        // Between 0.05 and 0.2: 0.1, 0.15, then the hundredths, each printed as written.
        let values = round_values_between(0.05, 0.2);
        assert_eq!(values[..3], [0.1, 0.15, 0.06]);
        assert_eq!(round_values_between(100.0, 1000.0).len(), ROUND_VALUES);
        let printed: Vec<String> = values.iter().map(|v| v.to_string()).collect();
        assert!(printed.iter().all(|p| p.len() <= 4), "{printed:?}");
        assert_eq!(values.len(), 2 + 12);
        assert!(values.iter().all(|&v| v > 0.05 && v < 0.2));
    }

    #[test]
    fn a_move_reads_the_pixel_whose_ray_it_shows() {
        // Pixel (x, output row r) of a W x H image under the moves traces the camera's
        // (x + columns, y + rows), y = H-1-r (r upside down); the reference wrote that ray
        // at output row H-1-y' (y' upside down): for every pixel of small images, the
        // index `shifted_from` gives, and whether `uncovered` says the ray lies past the
        // edge, as the definition gives them.
        for (width, height) in [(5, 4), (1, 3), (4, 1), (3, 3)] {
            for moves in [
                "row-offset=1",
                "row-offset=-2",
                "column-offset=1",
                "column-offset=-3",
                "row-offset=2,column-offset=-1",
                "upside-down",
                "upside-down,row-offset=1,column-offset=1",
                "upside-down,row-offset=-2",
                "row-offset=4",
            ] {
                let moves: Vec<Variant> = moves
                    .split(',')
                    .map(|v| Variant::parse(v).unwrap())
                    .collect();
                let options = Options::new(width, height);
                let moved = options.with_variants(&moves).unwrap();
                let from = shifted_from(&options, &moved, &moves).unwrap();
                let uncovered = uncovered(&moved);
                let (rows, columns) = offsets(&moves);
                let flipped = moves.iter().any(|v| v.kind == Kind::UpsideDown);
                let (w, h) = (width as i64, height as i64);
                for i in 0..width * height {
                    let (x, r) = ((i % width) as i64, (i / width) as i64);
                    let y = if flipped { r } else { h - 1 - r };
                    let (tx, ty) = (x + columns, y + rows);
                    let inside = (0..w).contains(&tx) && (0..h).contains(&ty);
                    let expected = inside.then(|| ((h - 1 - ty) * w + tx) as usize);
                    assert_eq!(from(i), expected, "{width}x{height} {moves:?} pixel {i}");
                    assert_eq!(
                        uncovered(i),
                        !inside,
                        "{width}x{height} {moves:?} pixel {i}"
                    );
                }
            }
        }
    }

    #[test]
    fn every_nth_picks_as_step_by_does() {
        // A mask of 200 pixels whose bits follow a pattern with runs and gaps.
        let pixels: usize = 200;
        let set = |i: usize| (i * 7 + i / 13) % 5 < 2 || (64..70).contains(&i);
        let mut mask = vec![0u64; pixels.div_ceil(64)];
        for i in (0..pixels).filter(|&i| set(i)) {
            mask[i / 64] |= 1 << (i % 64);
        }
        for every in [1, 2, 3, 7, 64, 65, 500] {
            for want in [true, false] {
                let expected: Vec<usize> = (0..pixels)
                    .filter(|&i| set(i) == want)
                    .step_by(every)
                    .collect();
                assert_eq!(every_nth(&mask, pixels, want, every), expected, "{every}");
            }
        }
    }

    #[test]
    fn the_roundest_number_of_a_range() {
        assert_eq!(roundest(65.3, 71.2), (70.0, 10.0));
        assert_eq!(roundest(20.0, 25.0), (20.0, 10.0));
        assert_eq!(roundest(60.0, 1000.0), (60.0, 10.0));
        assert_eq!(roundest(33.1, 33.9), (33.5, 0.5));
        assert_eq!(roundest(0.0, 7.3), (5.0, 5.0));
        assert_eq!(roundest(0.0, 14.05), (10.0, 10.0));
        // Steps below 1 give the decimals as written.
        assert_eq!(roundest(0.55, 0.65), (0.6, 0.1));
        assert_eq!(roundest(0.271, 0.29), (0.28, 0.01));
        assert_eq!(roundest(0.00711, 0.0074), (0.0072, 0.0001));
    }
}
