//! `compare --diagnose`: which of spec §7.3's variants explains a student's image.
//!
//! Each variant is rendered at the image's size and scored by its agreement with the
//! student's image (the share of pixels within the tolerance); the ones that agree better
//! than the reference does are listed, best first, and the best is tried together with
//! each other variant.
//! MAX_DIST is not guessed from a list: one render with long paths records each pixel's
//! bytes after each mirror bounce ([`render::path_agreement`]), which gives
//! the image
//! under every MAX_DIST at once, and the best D is read off ([`estimate_max_dist`]).

use super::{agreement, pixel_difference};
use crate::render::{self, Image, Kind, Options, Variant};
use crate::scene::Scene;
use serde::Serialize;

/// The longest MAX_DIST `--diagnose` considers: 30 times the course's 32.
pub const PROBE_LIMIT: f64 = 1000.0;

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
}

/// What one variant (or pair) scored.
struct Tried {
    variants: Vec<Variant>,
    agreement: f64,
    max_dist_range: Option<[f64; 2]>,
}

/// The variants that explain `student` better than `reference` (the image of `options`,
/// at `options`' size), best first; the best one together with another first where the
/// pair explains it better still. Empty when the images agree within `levels`
/// everywhere.
pub fn diagnose(
    scene: &Scene,
    options: &Options,
    reference: &Image,
    student: &Image,
    levels: u8,
) -> Vec<Diagnosis> {
    let before = agreement(reference, student, levels);
    if before >= 1.0 {
        return Vec::new();
    }
    let score = |variants: &[Variant]| -> Option<f64> {
        let options = variants
            .iter()
            .try_fold(*options, |o, &v| o.with_variant(v).ok())?;
        let image = render::render(scene, &options, |_| {});
        Some(agreement(&image, student, levels))
    };
    let mut found: Vec<Tried> = Vec::new();
    for variant in Variant::tried() {
        if variant.kernel() == Some(options.kernel) {
            continue;
        }
        if let Some(agreement) = score(&[variant])
            && agreement > before
        {
            found.push(Tried {
                variants: vec![variant],
                agreement,
                max_dist_range: None,
            });
        }
    }
    if let Some((d, range, agreement)) = estimate_max_dist(scene, options, student, levels)
        && agreement > before
    {
        found.push(Tried {
            variants: vec![Variant {
                value: Some(d),
                ..Variant::of(Kind::MaxDist)
            }],
            agreement,
            max_dist_range: Some(range),
        });
    }
    // Best first; a stable sort keeps spec §7.3's order among equals.
    found.sort_by(|a, b| b.agreement.total_cmp(&a.agreement));
    // The best one with each other variant: a second mistake often shows only once the
    // first is undone (an image upside down hides everything else).
    if let Some(best) = found.first().filter(|best| best.agreement < 1.0) {
        let first = best.variants[0];
        let mut estimated = found.iter().map(|t| t.variants[0]);
        let max_dist = estimated.rfind(|v| v.kind == Kind::MaxDist);
        let partners = Variant::tried().chain(max_dist);
        let pairs = partners
            .filter(|&partner| partner.id() != first.id())
            .filter_map(|partner| Some((partner, score(&[first, partner])?)));
        let top = pairs.max_by(|a, b| a.1.total_cmp(&b.1).then(std::cmp::Ordering::Greater));
        if let Some((partner, agreement)) = top
            && agreement > best.agreement
        {
            let range = match (first.kind, partner.kind) {
                (Kind::MaxDist, _) => best.max_dist_range,
                (_, Kind::MaxDist) => found.iter().find_map(|t| t.max_dist_range),
                _ => None,
            };
            found.insert(
                0,
                Tried {
                    variants: vec![first, partner],
                    agreement,
                    max_dist_range: range,
                },
            );
        }
    }
    found
        .into_iter()
        .map(|tried| Diagnosis {
            variants: tried.variants,
            agreement_before: before,
            agreement_after: tried.agreement,
            max_dist_range: tried.max_dist_range,
        })
        .collect()
}

/// The MAX_DIST D under which the scene's image agrees best with `student`, the range of
/// D that gives that same image, and the agreement; `None` if no D up to
/// [`PROBE_LIMIT`] changes the image. D is the roundest number in the range (70 rather
/// than 66.3).
pub fn estimate_max_dist(
    scene: &Scene,
    options: &Options,
    student: &Image,
    levels: u8,
) -> Option<(f64, [f64; 2], f64)> {
    let probe = Options {
        max_dist: PROBE_LIMIT.max(options.max_dist),
        ..*options
    };
    let (mut state, changes) = render::path_agreement(scene, &probe, |pixel, bytes| {
        pixel_difference(bytes, student.pixels[pixel]) <= levels
    });
    let mut agreeing = state.iter().filter(|&&s| s).count();
    // Agreement on each interval [start, next start) of D.
    let mut intervals: Vec<(f64, usize)> = vec![(0.0, agreeing)];
    for change in changes {
        let pixel = change.pixel as usize;
        agreeing = agreeing + usize::from(change.agrees) - usize::from(state[pixel]);
        state[pixel] = change.agrees;
        match intervals.last_mut() {
            Some(last) if last.0 == change.start => last.1 = agreeing,
            _ => intervals.push((change.start, agreeing)),
        }
    }
    let end = |i: usize| intervals.get(i + 1).map_or(probe.max_dist, |next| next.0);
    let current = intervals
        .iter()
        .rposition(|&(start, _)| start <= options.max_dist)?;
    let best = intervals.iter().map(|&(_, count)| count).max()?;
    if best <= intervals[current].1 {
        return None;
    }
    // Among the ranges that agree best, the one with the roundest D (the student wrote
    // 70, not 68.917), then the smallest.
    let (d, range) = (intervals.iter().enumerate())
        .filter(|&(_, &(_, count))| count == best)
        .map(|(i, &(low, _))| (roundest(low, end(i)), [low, end(i)]))
        .max_by(|((d1, step1), _), ((d2, step2), _)| step1.total_cmp(step2).then(d2.total_cmp(d1)))
        .map(|((d, _), range)| (d, range))?;
    Some((d, range, best as f64 / student.pixels.len().max(1) as f64))
}

/// The roundest number D with low <= D < high and D > 0, and its roundness: D is a
/// multiple of the largest step (…, 100, 50, 10, 5, 1, 0.5, 0.1, …) that is at most half
/// of `low` (or at most `high` when `low` is 0) and has a multiple in the range.
pub fn roundest(low: f64, high: f64) -> (f64, f64) {
    let scale = if low > 0.0 { low / 2.0 } else { high };
    let mut step = 10f64.powi(scale.log10().floor() as i32 + 1);
    for _ in 0..40 {
        for s in [step, step / 2.0] {
            if s <= scale {
                let multiple = (low / s).ceil().max(1.0) * s;
                if multiple < high {
                    return (multiple, s);
                }
            }
        }
        step /= 10.0;
    }
    (if low > 0.0 { low } else { high / 2.0 }, 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_roundest_number_of_a_range() {
        assert_eq!(roundest(65.3, 71.2), (70.0, 10.0));
        assert_eq!(roundest(20.0, 25.0), (20.0, 10.0));
        assert_eq!(roundest(60.0, 1000.0), (60.0, 10.0));
        assert_eq!(roundest(33.1, 33.9), (33.5, 0.5));
        assert_eq!(roundest(0.0, 7.3), (5.0, 5.0));
        assert_eq!(roundest(0.0, 14.05), (10.0, 10.0));
    }
}
