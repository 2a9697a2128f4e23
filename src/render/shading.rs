//! The material at a hit point: tiles (spec §5.4), textures (§5.8) and procedural
//! shaders (§5.5) vary the object's material over its surface.

use crate::scene::{Material, Object, Pattern, Shader, Texture, TextureMode};
use crate::shapes::Surface;
use glam::{DVec2, DVec3};
use std::f64::consts::{PI, TAU};

/// What texture tile mode needs of the projection: (W - 1, H - 1) and the world window.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Screen {
    /// Image width and height minus one, as reals.
    pub(crate) last_pixel: DVec2,
    /// World window width and height.
    pub(crate) window: DVec2,
}

/// `trunc(x)` as an integer (saturating for absurd values), as C's cast to int does.
fn trunc(x: f64) -> i64 {
    x.trunc() as i64
}

/// Which part of its pattern chose a material (for `legacy-rt trace`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PatternNote {
    /// One material everywhere.
    Plain,
    /// A tile of spec §5.4: relx, rely, and whether their sum is odd (the foreground).
    Tile {
        /// trunc(10000 + q.x / w).
        relx: i64,
        /// trunc(10000 + q.y / h).
        rely: i64,
        /// relx + rely odd: the first material.
        foreground: bool,
    },
    /// A texel of spec §5.8: its column and row from the bottom, and its value / 255.
    Texel {
        /// The texel's column, from the left.
        col: i64,
        /// Row, counted from the texture's bottom.
        row: i64,
        /// The texel, each channel byte / 255.
        value: DVec3,
    },
    /// A procedural shader of spec §5.5 and its value there: the stripe number s, or the
    /// colour wheel's angle t in radians.
    Shader {
        /// The shader of the record (stripes or colour wheel).
        shader: Shader,
        /// The stripe number s, or the colour wheel's angle t in radians.
        value: f64,
    },
}

/// The object's material at `surface`, and what chose it; with `other_tile`, a tiled
/// plane's other tile's (a decision forced the other way).
#[inline(always)]
pub(crate) fn material_and_pattern(
    object: &Object,
    surface: &Surface,
    screen: &Screen,
    other_tile: bool,
) -> (Material, PatternNote) {
    match &object.look.pattern {
        Pattern::Plain => (object.look.material, PatternNote::Plain),
        Pattern::Tiles { tile, background } => {
            let (relx, rely) = tile_index(surface.plane_xy, *tile);
            let foreground = is_foreground(relx, rely) != other_tile;
            let material = if foreground {
                object.look.material
            } else {
                **background
            };
            let note = PatternNote::Tile {
                relx,
                rely,
                foreground,
            };
            (material, note)
        }
        Pattern::Texture {
            texture,
            mode,
            size,
        } => {
            let (col, row) = texel_index(texture, *mode, surface.plane_xy, *size, screen);
            let [r, g, b] = texture.texels[(row * texture.width as i64 + col) as usize];
            let value = DVec3::new(r.into(), g.into(), b.into()) / 255.0;
            let material = Material {
                ambient: object.look.material.ambient * value,
                diffuse: object.look.material.diffuse * value,
                specular: object.look.material.specular,
            };
            (material, PatternNote::Texel { col, row, value })
        }
        Pattern::Shader { shader, origin } => {
            let v = surface.point - *origin;
            let (ambient, value) = match shader {
                Shader::Stripes => stripes(object.look.material.ambient, v),
                Shader::ColourWheel => colour_wheel(object.look.material.ambient, v),
            };
            let material = Material {
                ambient,
                ..object.look.material
            };
            let shader = *shader;
            (material, PatternNote::Shader { shader, value })
        }
    }
}

/// relx = trunc(10000 + q.x/w), rely = trunc(10000 + q.y/h) (spec §5.4).
fn tile_index(q: DVec2, tile: DVec2) -> (i64, i64) {
    (trunc(10000.0 + q.x / tile.x), trunc(10000.0 + q.y / tile.y))
}

/// The foreground material applies where relx + rely is odd (spec §5.4). The parity of
/// the sum is the exclusive-or of the low bits, which cannot overflow where both
/// truncations saturate.
fn is_foreground(relx: i64, rely: i64) -> bool {
    (relx ^ rely) & 1 == 1
}

/// The column and row (from the bottom) of the texel under plane coordinates `q`
/// (spec §5.8).
fn texel_index(
    texture: &Texture,
    mode: TextureMode,
    q: DVec2,
    size: DVec2,
    screen: &Screen,
) -> (i64, i64) {
    let (tw, th) = (texture.width as i64, texture.height as i64);
    match mode {
        TextureMode::Fit => (
            trunc(q.x / size.x * tw as f64).clamp(0, tw - 1),
            trunc(q.y / size.y * th as f64).clamp(0, th - 1),
        ),
        TextureMode::Tile => (
            trunc(screen.last_pixel.x * q.x / screen.window.x).rem_euclid(tw),
            trunc(screen.last_pixel.y * q.y / screen.window.y).rem_euclid(th),
        ),
    }
}

/// Shader 0: s = trunc(1000 + vx vy²/100 + vx vy/100); odd s removes red, even removes
/// blue. Returns the ambient and s.
fn stripes(ambient: DVec3, v: DVec3) -> (DVec3, f64) {
    let s = trunc(1000.0 + v.x * v.y * v.y / 100.0 + v.x * v.y / 100.0);
    let ambient = if s % 2 != 0 {
        DVec3::new(0.0, ambient.y, ambient.z)
    } else {
        DVec3::new(ambient.x, ambient.y, 0.0)
    };
    (ambient, s as f64)
}

/// Shader 1: with t the angle of (vx, vy) in [0, 2π), multiply r, g, b by 1 + cos 2t,
/// 1 + cos(2t + 2π/3), 1 + cos(2t + 4π/3). Returns the ambient and t.
fn colour_wheel(ambient: DVec3, v: DVec3) -> (DVec3, f64) {
    let t = v.y.atan2(v.x).rem_euclid(TAU);
    let wheel = DVec3::new(
        1.0 + (2.0 * t).cos(),
        1.0 + (2.0 * t + 2.0 * PI / 3.0).cos(),
        1.0 + (2.0 * t + 4.0 * PI / 3.0).cos(),
    );
    (ambient * wheel, t)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whether the foreground material applies at `q` (relx + rely odd).
    fn foreground_tile(q: DVec2, tile: DVec2) -> bool {
        let (relx, rely) = tile_index(q, tile);
        is_foreground(relx, rely)
    }

    #[test]
    fn tile_parity_is_that_of_relx_plus_rely() {
        let unit = DVec2::ONE;
        // (0.5, 0.5): 10000 + 10000 even, background; (1.5, 0.5): 10001 + 10000 odd.
        assert!(!foreground_tile(DVec2::new(0.5, 0.5), unit));
        assert!(foreground_tile(DVec2::new(1.5, 0.5), unit));
        // Negative q truncates toward zero: -0.5 gives 9999, -1.5 gives 9998.
        assert!(foreground_tile(DVec2::new(-0.5, 0.5), unit));
        assert!(!foreground_tile(DVec2::new(-1.5, 0.5), unit));
    }

    #[test]
    fn tile_parity_does_not_overflow_where_truncation_saturates() {
        // A valid tile size of 1e-300 makes q/w infinite: both truncations give i64::MAX,
        // whose sum overflows (it panicked before).
        let tiny = DVec2::splat(1e-300);
        assert!(!foreground_tile(DVec2::new(1.0, 1.0), tiny));
        assert!(foreground_tile(DVec2::new(1.0, -1.0), tiny));
    }

    #[test]
    fn stripes_parity_follows_the_formula() {
        let ambient = DVec3::new(4.0, 2.0, 4.0);
        // v = (10, 3): 1000 + 10*9/100 + 10*3/100 = 1001.2 -> 1001, odd: red removed.
        assert_eq!(
            stripes(ambient, DVec3::new(10.0, 3.0, 0.0)).0,
            DVec3::new(0.0, 2.0, 4.0)
        );
        // v = (1, 1): 1000.02 -> 1000, even: blue removed.
        assert_eq!(
            stripes(ambient, DVec3::new(1.0, 1.0, 0.0)).0,
            DVec3::new(4.0, 2.0, 0.0)
        );
    }

    #[test]
    fn colour_wheel_at_known_angles() {
        let one = DVec3::ONE;
        // t = 0: (1 + 1, 1 + cos 120°, 1 + cos 240°) = (2, 0.5, 0.5).
        let (w, _) = colour_wheel(one, DVec3::new(1.0, 0.0, 5.0));
        assert!((w - DVec3::new(2.0, 0.5, 0.5)).length() < 1e-15, "{w}");
        // t = 90°: 2t = 180°: (0, 1 + cos 300°, 1 + cos 420°) = (0, 1.5, 1.5).
        let (w, _) = colour_wheel(one, DVec3::new(0.0, 2.0, 0.0));
        assert!((w - DVec3::new(0.0, 1.5, 1.5)).length() < 1e-15, "{w}");
    }
}
