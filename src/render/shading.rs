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

/// The object's material at `surface`.
#[inline]
pub(crate) fn material_at(object: &Object, surface: &Surface, screen: &Screen) -> Material {
    match &object.pattern {
        Pattern::Plain => object.material,
        Pattern::Tiles { tile, background } => {
            if foreground_tile(surface.plane_xy, *tile) {
                object.material
            } else {
                *background
            }
        }
        Pattern::Texture {
            texture,
            mode,
            size,
        } => {
            let texel = texel(texture, *mode, surface.plane_xy, *size, screen);
            Material {
                ambient: object.material.ambient * texel,
                diffuse: object.material.diffuse * texel,
                specular: object.material.specular,
            }
        }
        Pattern::Shader { shader, origin } => {
            let v = surface.point - *origin;
            let ambient = match shader {
                Shader::Stripes => stripes(object.material.ambient, v),
                Shader::ColourWheel => colour_wheel(object.material.ambient, v),
            };
            Material {
                ambient,
                ..object.material
            }
        }
    }
}

/// relx = trunc(10000 + q.x/w), rely = trunc(10000 + q.y/h); the foreground material
/// applies where relx + rely is odd (spec §5.4). The parity of the sum is the exclusive-or
/// of the low bits, which cannot overflow where both truncations saturate.
fn foreground_tile(q: DVec2, tile: DVec2) -> bool {
    let relx = trunc(10000.0 + q.x / tile.x);
    let rely = trunc(10000.0 + q.y / tile.y);
    (relx ^ rely) & 1 == 1
}

/// The texel under plane coordinates `q`, each channel byte / 255 (spec §5.8).
fn texel(texture: &Texture, mode: TextureMode, q: DVec2, size: DVec2, screen: &Screen) -> DVec3 {
    let (tw, th) = (texture.width as i64, texture.height as i64);
    let (col, row) = match mode {
        TextureMode::Fit => (
            trunc(q.x / size.x * tw as f64).clamp(0, tw - 1),
            trunc(q.y / size.y * th as f64).clamp(0, th - 1),
        ),
        TextureMode::Tile => (
            trunc(screen.last_pixel.x * q.x / screen.window.x).rem_euclid(tw),
            trunc(screen.last_pixel.y * q.y / screen.window.y).rem_euclid(th),
        ),
    };
    let [r, g, b] = texture.texels[(row * tw + col) as usize];
    DVec3::new(r.into(), g.into(), b.into()) / 255.0
}

/// Shader 0: s = trunc(1000 + vx vy²/100 + vx vy/100); odd s removes red, even removes blue.
fn stripes(ambient: DVec3, v: DVec3) -> DVec3 {
    let s = trunc(1000.0 + v.x * v.y * v.y / 100.0 + v.x * v.y / 100.0);
    if s % 2 != 0 {
        DVec3::new(0.0, ambient.y, ambient.z)
    } else {
        DVec3::new(ambient.x, ambient.y, 0.0)
    }
}

/// Shader 1: with t the angle of (vx, vy) in [0, 2π), multiply r, g, b by 1 + cos 2t,
/// 1 + cos(2t + 2π/3), 1 + cos(2t + 4π/3).
fn colour_wheel(ambient: DVec3, v: DVec3) -> DVec3 {
    let t = v.y.atan2(v.x).rem_euclid(TAU);
    let wheel = DVec3::new(
        1.0 + (2.0 * t).cos(),
        1.0 + (2.0 * t + 2.0 * PI / 3.0).cos(),
        1.0 + (2.0 * t + 4.0 * PI / 3.0).cos(),
    );
    ambient * wheel
}

#[cfg(test)]
mod tests {
    use super::*;

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
            stripes(ambient, DVec3::new(10.0, 3.0, 0.0)),
            DVec3::new(0.0, 2.0, 4.0)
        );
        // v = (1, 1): 1000.02 -> 1000, even: blue removed.
        assert_eq!(
            stripes(ambient, DVec3::new(1.0, 1.0, 0.0)),
            DVec3::new(4.0, 2.0, 0.0)
        );
    }

    #[test]
    fn colour_wheel_at_known_angles() {
        let one = DVec3::ONE;
        // t = 0: (1 + 1, 1 + cos 120°, 1 + cos 240°) = (2, 0.5, 0.5).
        let w = colour_wheel(one, DVec3::new(1.0, 0.0, 5.0));
        assert!((w - DVec3::new(2.0, 0.5, 0.5)).length() < 1e-15, "{w}");
        // t = 90°: 2t = 180°: (0, 1 + cos 300°, 1 + cos 420°) = (0, 1.5, 1.5).
        let w = colour_wheel(one, DVec3::new(0.0, 2.0, 0.0));
        assert!((w - DVec3::new(0.0, 1.5, 1.5)).length() < 1e-15, "{w}");
    }
}
