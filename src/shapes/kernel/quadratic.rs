//! Real roots of a t² + b t + c = 0, the equation every quadric hit reduces to.
//!
//! The course notes use the textbook (-b ± sqrt(b² - 4ac)) / 2a (note 002 warns that it
//! is "not numerically good"). Here the root of larger magnitude comes from
//! q = -(b + sign(b) sqrt(b² - 4ac)) / 2 as q / a and the other as c / q, so neither root
//! is formed by subtracting nearly equal numbers. When a = 0 the equation is linear.

/// Both real roots in ascending order (equal for a double root or a linear equation), or
/// `None` when there is no real root.
pub(crate) type Roots = Option<[f64; 2]>;

/// Solves a t² + b t + c = 0. A negative discriminant gives `None`; a zero one a double
/// root; a = 0 the single root of b t + c = 0 (or `None` when b = 0 too).
#[inline]
pub(crate) fn solve_quadratic(a: f64, b: f64, c: f64) -> Roots {
    solve_quadratic_with_slope(a, b, c).map(|(roots, _)| roots)
}

/// [`solve_quadratic`], and the size of the slope |2 a t + b| at either root, which is
/// sqrt(b² - 4ac) at both (|b| for the linear equation): what the accurate kernel divides
/// a root's error by.
#[inline(always)]
pub(crate) fn solve_quadratic_with_slope(a: f64, b: f64, c: f64) -> Option<([f64; 2], f64)> {
    if a == 0.0 {
        // Linear: a ray parallel to a cylinder's axis, along a cone's generator, or along
        // a paraboloid's axis (spec §5.6).
        if b == 0.0 {
            return None;
        }
        let t = -c / b;
        return Some(([t, t], b.abs()));
    }
    let discriminant = b * b - 4.0 * a * c;
    if discriminant < 0.0 || discriminant.is_nan() {
        return None;
    }
    let root = discriminant.sqrt();
    let q = -0.5 * (b + root.copysign(b));
    let far = q / a;
    // q = 0 only when b = 0 and the discriminant is 0, i.e. c = 0: a double root at 0.
    let near = if q == 0.0 { 0.0 } else { c / q };
    Some((if far < near { [far, near] } else { [near, far] }, root))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roots_of_a_product_of_known_factors() {
        // (t - 2)(t - 5) = t² - 7t + 10.
        assert_eq!(solve_quadratic(1.0, -7.0, 10.0), Some([2.0, 5.0]));
        // 2(t + 1)(t - 3) = 2t² - 4t - 6.
        assert_eq!(solve_quadratic(2.0, -4.0, -6.0), Some([-1.0, 3.0]));
    }

    #[test]
    fn double_root_negative_discriminant_and_linear_cases() {
        assert_eq!(solve_quadratic(1.0, -4.0, 4.0), Some([2.0, 2.0]));
        assert_eq!(solve_quadratic(1.0, 0.0, 1.0), None);
        assert_eq!(solve_quadratic(0.0, 2.0, -6.0), Some([3.0, 3.0]));
        assert_eq!(solve_quadratic(0.0, 0.0, 1.0), None);
        assert_eq!(solve_quadratic(3.0, 0.0, 0.0), Some([0.0, 0.0]));
    }

    #[test]
    fn small_root_keeps_its_digits_where_the_textbook_formula_cancels() {
        // t² - 1e8 t + 1 = 0 has roots 1e8 - 1e-8 and 1 / that, about 1e-8 + 1e-24.
        let [small, _] = solve_quadratic(1.0, -1e8, 1.0).unwrap();
        let textbook = (1e8 - (1e16f64 - 4.0).sqrt()) / 2.0;
        assert!((small - 1e-8).abs() <= 1e-8 * 1e-15, "{small}");
        assert!((textbook - 1e-8).abs() > 1e-8 * 0.1, "{textbook}");
    }
}
