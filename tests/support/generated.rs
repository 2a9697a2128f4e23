//! A generated scene family for the scaling measurements of issue 6: `count` bounded
//! objects (spheres and the quadrics 21-24, in turn, with axes in several directions)
//! on a grid that fills the view from z = -6 to z = -30, above a floor plane, lit by one
//! light. Each object is about a third of its grid cell, so most are visible, and every
//! camera ray passes many boxes. The same count gives the same text.

use std::fmt::Write as _;

/// The scene text with `count` objects.
pub fn many_objects(count: usize) -> String {
    let mut text = String::from("8 6           world window\n0 0 3         viewpoint\n\n");
    text.push_str(
        "14            floor\n0.5 0.5 0.5\n2 2 2\n0 0 0\n0 1 0         normal\n0 -4 0        point\n\n",
    );
    let side = (count as f64).cbrt().ceil() as usize;
    let axes = ["0 1 0", "1 0 0", "0 0 1", "1 1 0", "0 1 1", "-1 1 1"];
    for i in 0..count {
        let (ix, iy, iz) = (i % side, (i / side) % side, i / (side * side));
        let z = -6.0 - 24.0 * (iz as f64 + 0.5) / side as f64;
        // The window's half-size at this depth, seen from the eye at z = 3.
        let spread = (3.0 - z) / 3.0;
        let cell = |index: usize, half: f64| {
            (2.0 * (index as f64 + 0.5) / side as f64 - 1.0) * half * spread * 0.9
        };
        let (x, y) = (cell(ix, 4.0), cell(iy, 3.0));
        let size = 8.0 * spread / side as f64 * 0.3;
        let kind = i % 5;
        let code = [13, 22, 23, 21, 24][kind];
        let colour = [(4, 2, 2), (2, 4, 2), (2, 2, 4), (4, 4, 2), (2, 4, 4)][kind];
        writeln!(text, "{code}            object {i}").unwrap();
        writeln!(text, "{} {} {}   ambient", colour.0, colour.1, colour.2).unwrap();
        writeln!(text, "{} {} {}   diffuse", colour.0, colour.1, colour.2).unwrap();
        writeln!(text, "0 0 0         specular").unwrap();
        writeln!(text, "{x} {y} {z}   centre").unwrap();
        if code == 13 {
            writeln!(text, "{size}   radius\n").unwrap();
        } else {
            writeln!(text, "{}   axis", axes[i % axes.len()]).unwrap();
            writeln!(text, "{} {}   radius and height", size * 0.6, size).unwrap();
            if code == 24 {
                writeln!(text, "{}   waist radius", size * 0.3).unwrap();
            }
            text.push('\n');
        }
    }
    text.push_str("10            light\n20 20 20\n-5 8 2        location\n");
    text
}
