//! Which pixels a variant can change: what `compare --diagnose` needs to know a
//! candidate's exact agreement without rendering a whole image.
//!
//! A variant changes the image only where its rule is consulted with another outcome,
//! and the trace under the reference's rules and under the variant's is the same up to
//! that point: so the point lies on the reference's own path. While the reference
//! renders, each pixel keeps a summary of its path ([`Paths`]): the objects its camera
//! and mirror rays hit, those that block its shadow rays, the lights that add to it or
//! are blocked, and the bytes its colour gives under the other byte rules. A variant of
//! one record ([`Reach::of`]) can change only the pixels whose summary names that record
//! (hidden, unlit, no-mirror, flipped-normal, facing-normals, tile-parity and
//! shadow-epsilon act at hits on the object; no-shadow where it was the shadow ray's
//! first blocker, since any other blocker still blocks; no-light, unshadowed and
//! square-falloff where the light added something or was blocked); one-bounce only
//! where a second mirror ray was traced; far-clip=D only where a camera or mirror ray's
//! hit or a shadow ray's blocker lay at D or beyond (the path keeps a power of two above
//! its farthest); a byte rule changes a
//! pixel's bytes by at most one level per channel, which the summary holds. The other
//! variants (the camera's, the divisor, geometry that may be hit where it was not) can
//! change any pixel.

#[cfg(doc)]
use crate::render::variant::Bytes;
use crate::render::variant::{Kind, Reads, Site, Variant};
use crate::render::{Override, Rays};
use crate::scene::Scene;
use glam::DVec3;

/// One pixel's path in the reference, in 8 bytes: per object hit, per shadow blocker and
/// per light a bit of its index modulo the field's width (indices that share a bit all
/// count as named: a pixel is never missed, at worst one more is re-traced), how far its
/// farthest hit or blocker lay (a power of two at or above it), the
/// steps its bytes take under round-bytes and scale-256, whether MAX_DIST ended it, and
/// whether it went on past its first mirror bounce.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Paths(u64);

/// A field of [`Paths`]: its first bit and its width.
#[derive(Clone, Copy)]
struct Field(u32, u32);

const HITS: Field = Field(0, 28);
/// The farthest hit's or first blocker's t, as [`far_bucket`] gives it (4 bits).
const FAR: u32 = 28;
const BLOCKERS: Field = Field(32, 12);
const LIGHTS: Field = Field(44, 12);
/// Three bits per rule: whether each channel's byte is one level above the reference's.
const ROUND: u32 = 56;
const SCALE_256: u32 = 59;
/// Whether MAX_DIST ended the path (spec §4.2 step 1).
const CUT: u64 = 1 << 62;
/// Whether a second mirror ray was traced (spec §4.5's recursion past one bounce): what
/// one-bounce can change.
const DEEP: u64 = 1 << 63;

impl Field {
    /// The bit of `index`.
    fn bit(self, index: usize) -> u64 {
        1 << (self.0 + (index % self.1 as usize) as u32)
    }
}

impl Paths {
    /// The paths whose bits are `bits` ([`Paths::bits`]).
    pub(crate) fn from_bits(bits: u64) -> Paths {
        Paths(bits)
    }

    /// The bits, to store.
    pub(crate) fn bits(self) -> u64 {
        self.0
    }

    /// A camera or mirror ray hit `object`.
    pub(crate) fn hit(&mut self, object: usize) {
        self.0 |= HITS.bit(object);
    }

    /// `object` blocked a shadow ray toward `light`.
    pub(crate) fn blocked(&mut self, object: usize, light: usize) {
        self.0 |= BLOCKERS.bit(object) | LIGHTS.bit(light);
    }

    /// A camera or mirror ray's closest hit, or a shadow ray's blocker (the first found,
    /// no nearer than the nearest), lay at `t`: the path's farthest is kept.
    #[inline(always)]
    pub(crate) fn far(&mut self, t: f64) {
        let bucket = self.far_bucket().max(far_bucket(t));
        self.0 = self.0 & !(0b1111 << FAR) | u64::from(bucket) << FAR;
    }

    /// The bucket of the path's farthest hit or blocker ([`far_bucket`]; 0 for none).
    fn far_bucket(self) -> u8 {
        (self.0 >> FAR & 0b1111) as u8
    }

    /// MAX_DIST ended the path.
    pub(crate) fn cut(&mut self) {
        self.0 |= CUT;
    }

    /// A ray was traced at recursion depth `depth` (0: the camera ray).
    pub(crate) fn segment(&mut self, depth: usize) {
        self.0 |= u64::from(depth >= 2) * DEEP;
    }

    /// `light` added something.
    pub(crate) fn lit(&mut self, light: usize) {
        self.0 |= LIGHTS.bit(light);
    }

    /// Whether a camera or mirror ray may hit `object`: it did, or an object that shares
    /// its bit did (never with 28 objects or fewer).
    pub(crate) fn may_hit(self, object: usize) -> bool {
        self.0 & HITS.bit(object) != 0
    }

    /// Whether this path may take the decision `flip` forces the other way: it hits the
    /// object (by camera or mirror ray; a tile's colour and a mirror ray too), or the
    /// object blocks one of its shadow rays, or the light's term is consulted, or
    /// MAX_DIST ended it.
    pub(crate) fn may_take(self, flip: &Override) -> bool {
        let bit = match *flip {
            Override::Miss {
                object,
                rays: Rays::Shadow,
            } => BLOCKERS.bit(object),
            Override::Miss { object, .. }
            | Override::Tile { object }
            | Override::NoBounce { object } => HITS.bit(object),
            Override::Shadow { light, .. } => LIGHTS.bit(light),
            Override::NeverCut => CUT,
        };
        self.0 & bit != 0
    }

    /// The colour's bytes are `bytes` under the reference's rule (spec §4.7's truncation):
    /// the steps under the other rules. [`Bytes::byte`]'s byte exceeds `bytes` exactly
    /// where its value before the cast reaches the next integer; a byte of 255 has no
    /// step above it, and below 255 the channel is below 1 (or negative, or NaN, which
    /// reach nothing), so no clamp is needed.
    pub(crate) fn colour(&mut self, colour: DVec3, bytes: [u8; 3]) {
        let mut steps = 0;
        for (c, (channel, byte)) in colour.to_array().into_iter().zip(bytes).enumerate() {
            let next = f64::from(byte) + 1.0;
            let below = byte < 255;
            let round = below && channel * 255.0 + 0.5 >= next;
            let scaled = below && channel * 256.0 >= next;
            steps |= u64::from(round) << (ROUND + c as u32)
                | u64::from(scaled) << (SCALE_256 + c as u32);
        }
        self.0 |= steps;
    }

    /// The bytes of this pixel under the byte rule `rule` (round-bytes or scale-256),
    /// from the reference's `bytes`; the reference's for any other.
    pub fn bytes(self, rule: Option<Kind>, bytes: [u8; 3]) -> [u8; 3] {
        Steps::of(rule).apply(self, bytes)
    }
}

/// Where a byte rule's steps lie in [`Paths`]: the first of their three bits, and a mask
/// that keeps them (none for the reference's own rule). Found once for a pass over the
/// pixels, it steps each without a branch.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Steps {
    first: u32,
    mask: u64,
}

impl Steps {
    /// The steps of `rule` (round-bytes or scale-256); none for any other.
    pub(crate) fn of(rule: Option<Kind>) -> Steps {
        let first = match rule {
            Some(Kind::RoundBytes) => ROUND,
            Some(Kind::Scale256) => SCALE_256,
            _ => return Steps { first: 0, mask: 0 },
        };
        Steps { first, mask: 0b111 }
    }

    /// `bytes` stepped as `paths` holds under this rule.
    #[inline]
    pub(crate) fn apply(self, paths: Paths, bytes: [u8; 3]) -> [u8; 3] {
        let [r, g, b, _] = self.apply_packed(paths, packed(bytes)).to_le_bytes();
        [r, g, b]
    }

    /// [`Steps::apply`] on a pixel packed in a word (red the low byte, [`packed`]): each
    /// step added to its byte at once (a byte that steps is below 255: no carry).
    #[inline]
    fn apply_packed(self, paths: Paths, bytes: u32) -> u32 {
        let steps = (paths.0 >> self.first & self.mask) as u32;
        bytes + (steps & 1 | (steps & 2) << 7 | (steps & 4) << 14)
    }
}

/// A pixel's bytes in a word, red the low byte: compared and stepped whole.
#[inline]
pub(crate) fn packed([r, g, b]: [u8; 3]) -> u32 {
    u32::from_le_bytes([r, g, b, 0])
}

/// The bucket of a hit's or blocker's `t` (> 0) in [`Paths`]' four bits: b below 15
/// says t <= 2^(b - 4) (0 for t up to 1/16, 14 for t up to 1024); 15 says nothing (t
/// beyond 1024, or not finite). From the exponent of t, rounded up: no logarithm.
fn far_bucket(t: f64) -> u8 {
    let bits = t.to_bits();
    let exponent = (bits >> 52 & 0x7ff) as i64 - 1023;
    let above = i64::from(bits & ((1 << 52) - 1) != 0);
    (exponent + above + 4).clamp(0, 15) as u8
}

/// The least bucket ([`far_bucket`]) whose hits far-clip=`d` may clip: a path whose
/// farthest lies in a lower one lay nearer than d all along.
fn clipped_from(d: f64) -> u8 {
    (0..15)
        .find(|&b| (2f64).powi(i32::from(b) - 4) >= d)
        .unwrap_or(15)
}

/// [`Reach`]'s bucket without a far clip: above every bucket.
const NO_CLIP: u8 = 16;

/// The pixels a set of variants can change, as far as [`Paths`] tells.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Reach {
    /// The bits of the records they act on: a pixel whose paths share one may change.
    records: u64,
    /// far-clip's least bucket ([`clipped_from`]): a pixel whose farthest hit lies in it
    /// or above may change; [`NO_CLIP`] without a far clip.
    clipped: u8,
    /// The byte rule among them, whose bytes the paths hold.
    bytes: Option<Kind>,
}

impl Reach {
    /// What `variants`, applied on top of a reference rendered with `reference` (the
    /// variants already in its options), can change; `None` when it may be any pixel.
    pub fn of(scene: &Scene, reference: &[Variant], variants: &[Variant]) -> Option<Reach> {
        // The steps held are from truncated bytes.
        if reference.iter().any(|v| v.row().site == Site::Bytes) {
            return None;
        }
        let mut reach = Reach {
            records: 0,
            clipped: NO_CLIP,
            bytes: None,
        };
        for variant in variants {
            if variant.row().site == Site::Bytes && reach.bytes.is_none() {
                reach.bytes = Some(variant.kind);
                continue;
            }
            // What of the path the variant's rule is read on (its row says).
            match variant.row().reads {
                // At most one bounce: the paths that took a second.
                Reads::SecondBounce => reach.records |= DEEP,
                // A far clip: the paths that met something at its distance or beyond.
                Reads::Distances => {
                    let from = clipped_from(variant.value.unwrap_or(f64::INFINITY));
                    reach.clipped = reach.clipped.min(from);
                }
                // The records from a line on, gone: where a path met any of them.
                Reads::Records => {
                    let line = variant.line?;
                    let gone = |at: usize| at >= line;
                    for (object, _) in
                        (scene.objects.iter().enumerate()).filter(|(_, o)| gone(o.line))
                    {
                        reach.records |= HITS.bit(object) | BLOCKERS.bit(object);
                    }
                    for (light, _) in
                        (scene.lights.iter().enumerate()).filter(|(_, l)| gone(l.line))
                    {
                        reach.records |= LIGHTS.bit(light);
                    }
                }
                reads => {
                    let line = variant.line?;
                    let object = scene.objects.iter().position(|o| o.line == line);
                    let light = scene.lights.iter().position(|l| l.line == line);
                    reach.records |= match (reads, object, light) {
                        (Reads::Hits, Some(object), _) => HITS.bit(object),
                        (Reads::Blockers, Some(object), _) => BLOCKERS.bit(object),
                        (Reads::Lights, _, Some(light)) => LIGHTS.bit(light),
                        // Geometry (no-z-rule, cone-scale, nearer-root) may be hit where
                        // it was not.
                        _ => return None,
                    };
                }
            }
        }
        Some(reach)
    }

    /// Whether any pixel may need to be traced again (not for a byte rule alone).
    pub fn traces(self) -> bool {
        self.records != 0 || self.clipped != NO_CLIP
    }

    /// Whether a pixel whose path is `paths` may change: it must be traced again.
    pub fn touches(self, paths: Paths) -> bool {
        paths.0 & self.records != 0 || paths.far_bucket() >= self.clipped
    }

    /// The byte rule among the variants, if any: the bytes of the pixels it does not touch
    /// are the reference's stepped under it.
    pub fn byte_rule(self) -> Option<Kind> {
        self.bytes
    }

    /// The bytes of a pixel it does not touch, from the reference's `bytes`.
    pub fn untouched(self, paths: Paths, bytes: [u8; 3]) -> [u8; 3] {
        paths.bytes(self.bytes, bytes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_steps_of_the_other_byte_rules() {
        // 0.5: 127.5 truncates to 127, rounds to 128; 256 · 0.5 = 128.
        // 0.1: 25.5 → 25, 26; 25.6 → 25.
        // 1.0: 255 under every rule.
        let mut paths = Paths::default();
        let colour = DVec3::new(0.5, 0.1, 1.0);
        let bytes = [127, 25, 255];
        paths.colour(colour, bytes);
        assert_eq!(paths.bytes(Some(Kind::RoundBytes), bytes), [128, 26, 255]);
        assert_eq!(paths.bytes(Some(Kind::Scale256), bytes), [128, 25, 255]);
        assert_eq!(paths.bytes(None, bytes), bytes);
    }

    #[test]
    fn the_steps_agree_with_the_byte_rules_everywhere() {
        use crate::render::variant::Bytes;
        // Every byte's edges and middles, and what lies outside [0, 1].
        let mut channels: Vec<f64> = (0..=256)
            .flat_map(|k| {
                let edge = f64::from(k) / 255.0;
                [
                    edge,
                    edge.next_down(),
                    edge.next_up(),
                    (f64::from(k) + 0.5) / 255.0,
                ]
            })
            .collect();
        channels.extend([f64::NAN, -1.0, 2.0, f64::INFINITY, f64::NEG_INFINITY]);
        for c in channels {
            let colour = DVec3::splat(c);
            let bytes = [Bytes::Truncate.byte(c); 3];
            let mut paths = Paths::default();
            paths.colour(colour, bytes);
            for (kind, rule) in [
                (Kind::RoundBytes, Bytes::Round),
                (Kind::Scale256, Bytes::Scale256),
            ] {
                assert_eq!(paths.bytes(Some(kind), bytes), [rule.byte(c); 3], "{c:e}");
            }
        }
    }

    #[test]
    fn a_far_bucket_bounds_its_t_and_far_clip_touches_what_may_lie_beyond() {
        // b < 15: t <= 2^(b-4), and t > 2^(b-5) (the bucket is the least that holds it).
        for t in [
            1e-9, 0.0625, 0.07, 0.5, 1.0, 1.5, 7.9, 8.0, 8.000001, 10.0, 1000.0,
        ] {
            let b = far_bucket(t);
            let bound = (2f64).powi(i32::from(b) - 4);
            assert!(t <= bound, "{t}: {b}");
            assert!(b == 0 || t > bound / 2.0, "{t}: {b}");
        }
        assert_eq!(far_bucket(2000.0), 15);
        assert_eq!(far_bucket(f64::INFINITY), 15);
        // far-clip=10 clips hits at t >= 10: buckets up to 7 (t <= 8) are untouched, 8 not.
        assert_eq!(clipped_from(10.0), 8);
        assert_eq!(clipped_from(8.0), 7);
        assert_eq!(clipped_from(5000.0), 15);
        let (mut near, mut far) = (Paths::default(), Paths::default());
        near.far(3.0);
        near.far(7.5);
        far.far(7.5);
        far.far(12.0);
        far.far(2.0);
        let reach = Reach {
            records: 0,
            clipped: clipped_from(10.0),
            bytes: None,
        };
        assert!(!reach.touches(near) && reach.touches(far));
    }

    #[test]
    fn indices_that_share_a_bit_are_all_named() {
        let mut paths = Paths::default();
        paths.hit(3);
        let reach = |object: usize| Reach {
            records: HITS.bit(object),
            clipped: NO_CLIP,
            bytes: None,
        };
        assert!(reach(3).touches(paths));
        assert!(reach(31).touches(paths));
        assert!(!reach(4).touches(paths));
        paths.blocked(4, 0);
        assert!(!reach(4).touches(paths), "a blocker is not a hit");
    }
}
