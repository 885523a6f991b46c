//! Colours of the pictures: one fill per face type, and the blue → red colour map of the density
//! maps.
//!
//! The type palette is Paul Tol's "muted" qualitative scheme (designed to stay distinct under the
//! common colour-vision deficiencies and in grey print), in his order. None of its colours is close
//! to the white background (the lightest, sand, has CIE L* 82 against white's 100), so a cell
//! never looks like a hole. Past nine types the colours repeat, darker each round; the legend names
//! every type with its notation.
//!
//! The density colour map is ColorBrewer's RdYlBu reversed (blue for empty, through pale yellow, to
//! red for full), diverging and readable by colour-blind viewers.

/// An sRGB colour.
pub type Rgb = [u8; 3];

/// Paul Tol's muted scheme: rose, indigo, sand, green, cyan, wine, teal, olive, purple.
pub const MUTED: [Rgb; 9] = [
    [0xCC, 0x66, 0x77],
    [0x33, 0x22, 0x88],
    [0xDD, 0xCC, 0x77],
    [0x11, 0x77, 0x33],
    [0x88, 0xCC, 0xEE],
    [0x88, 0x22, 0x55],
    [0x44, 0xAA, 0x99],
    [0x99, 0x99, 0x33],
    [0xAA, 0x44, 0x99],
];

/// The fill colour of face type `ty`.
pub fn type_colour(ty: usize) -> Rgb {
    let base = MUTED[ty % MUTED.len()];
    // Each further round of nine is 20% darker than the one before (at most three darker rounds).
    let round = ((ty / MUTED.len()).min(3)) as f64;
    let k = 0.8f64.powf(round);
    base.map(|c| (f64::from(c) * k).round() as u8)
}

/// The outline colour of a cell of type `ty`: its fill, darkened.
pub fn outline_colour(ty: usize) -> Rgb {
    darker(type_colour(ty))
}

/// A colour darkened to 45% (outlines of cells and legend swatches).
pub fn darker(c: Rgb) -> Rgb {
    c.map(|v| (f64::from(v) * 0.45).round() as u8)
}

/// `#rrggbb`.
pub fn hex(c: Rgb) -> String {
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

/// The stops of the density colour map (ColorBrewer RdYlBu, reversed), at 0, 0.1, …, 1.
const DENSITY_STOPS: [Rgb; 11] = [
    [0x31, 0x36, 0x95],
    [0x45, 0x75, 0xb4],
    [0x74, 0xad, 0xd1],
    [0xab, 0xd9, 0xe9],
    [0xe0, 0xf3, 0xf8],
    [0xff, 0xff, 0xbf],
    [0xfe, 0xe0, 0x90],
    [0xfd, 0xae, 0x61],
    [0xf4, 0x6d, 0x43],
    [0xd7, 0x30, 0x27],
    [0xa5, 0x00, 0x26],
];

/// The colour of density `d` (clamped to [0, 1]): dark blue for 0, pale yellow for 1/2, dark red
/// for 1, linear between the stops.
pub fn density_colour(d: f64) -> Rgb {
    let x = if d.is_finite() {
        d.clamp(0.0, 1.0)
    } else {
        0.0
    } * 10.0;
    let i = (x.floor() as usize).min(9);
    let t = x - i as f64;
    let (a, b) = (DENSITY_STOPS[i], DENSITY_STOPS[i + 1]);
    [0, 1, 2].map(|k| (f64::from(a[k]) * (1.0 - t) + f64::from(b[k]) * t).round() as u8)
}

/// CIE L* (lightness, 0–100) of an sRGB colour.
pub fn lightness(c: Rgb) -> f64 {
    let lin = |v: u8| {
        let v = f64::from(v) / 255.0;
        if v <= 0.04045 {
            v / 12.92
        } else {
            ((v + 0.055) / 1.055).powf(2.4)
        }
    };
    let y = 0.2126 * lin(c[0]) + 0.7152 * lin(c[1]) + 0.0722 * lin(c[2]);
    if y > 216.0 / 24389.0 {
        116.0 * y.cbrt() - 16.0
    } else {
        y * 24389.0 / 27.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_type_colour_is_close_to_white_and_the_first_nine_are_distinct() {
        for t in 0..40 {
            assert!(
                lightness(type_colour(t)) < 85.0,
                "type {t}: {}",
                hex(type_colour(t))
            );
        }
        for a in 0..9 {
            for b in a + 1..9 {
                let (x, y) = (type_colour(a), type_colour(b));
                let d: i32 = (0..3).map(|k| (x[k] as i32 - y[k] as i32).abs()).sum();
                assert!(d > 60, "{} and {} are too close", hex(x), hex(y));
            }
        }
    }

    #[test]
    fn the_density_map_runs_from_blue_to_red() {
        assert_eq!(density_colour(0.0), [0x31, 0x36, 0x95]);
        assert_eq!(density_colour(1.0), [0xa5, 0x00, 0x26]);
        assert_eq!(density_colour(0.5), [0xff, 0xff, 0xbf]);
        assert_eq!(density_colour(f64::NAN), density_colour(0.0));
        let c = density_colour(0.25);
        assert!(c[2] > c[0], "a quarter is still blue: {c:?}");
    }
}
