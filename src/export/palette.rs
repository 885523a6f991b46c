//! Colours of the pictures: one fill per face type, and the viridis colour map of the density
//! maps.
//!
//! The type palette starts with Paul Tol's "muted" qualitative scheme (designed to stay distinct
//! under the common colour-vision deficiencies and in grey print), in his order, and goes on with
//! fifteen colours chosen here, greedily, each the one farthest (CIE L*a*b*, ΔE76) from every
//! colour before it among the sRGB colours of steps 0x11 with lightness L* 30–80 and chroma at
//! most 60 (as muted as Tol's): so the first 24 types are pairwise at least ΔE 22.8 apart (the
//! least distance inside Tol's nine; a test keeps it). None is close to the white background (the
//! lightest, sand, has L* 82 against white's 100), so a cell never looks like a hole. Past 24
//! types the colours repeat, darker each round; the legend names every type with its notation.
//!
//! The density colour map is viridis (van der Walt and Smith's perceptually uniform sequential map,
//! the eleven stops of `viridis(11)`): dark violet for empty, through blue and green, to yellow for
//! full — lightness grows with density, so it reads in grey print and for colour-blind viewers. A
//! density is one-sided (0 to 1), so a sequential map, not a diverging one. Blocks outside the
//! structure are drawn in [`OUTSIDE`], off the map, so that they are not read as empty holes.

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

/// The fifteen colours after Tol's nine (module doc: each the farthest from all before it).
const MORE: [Rgb; 15] = [
    [0x88, 0x99, 0xFF],
    [0x44, 0x55, 0x77],
    [0x88, 0x44, 0x00],
    [0x55, 0x55, 0x33],
    [0xDD, 0xBB, 0xBB],
    [0xFF, 0x99, 0x66],
    [0xFF, 0xAA, 0xEE],
    [0x44, 0xDD, 0x99],
    [0x00, 0x88, 0xCC],
    [0x00, 0x55, 0x55],
    [0x77, 0x44, 0x44],
    [0x77, 0xBB, 0x55],
    [0xAA, 0x99, 0xCC],
    [0x77, 0x88, 0x88],
    [0x99, 0x22, 0x22],
];

/// The number of distinct type colours before they repeat darker.
pub const DISTINCT_TYPES: usize = MUTED.len() + MORE.len();

/// The fill colour of face type `ty`.
pub fn type_colour(ty: usize) -> Rgb {
    let i = ty % DISTINCT_TYPES;
    let base = match MUTED.get(i) {
        Some(&c) => c,
        None => MORE[i - MUTED.len()],
    };
    // Each further round of 24 is 20% darker than the one before (at most three darker rounds).
    let round = ((ty / DISTINCT_TYPES).min(3)) as f64;
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

/// The stops of the density colour map (viridis), at 0, 0.1, …, 1.
const DENSITY_STOPS: [Rgb; 11] = [
    [0x44, 0x01, 0x54],
    [0x48, 0x25, 0x76],
    [0x41, 0x44, 0x87],
    [0x35, 0x60, 0x8D],
    [0x2A, 0x78, 0x8E],
    [0x21, 0x90, 0x8C],
    [0x22, 0xA8, 0x84],
    [0x43, 0xBF, 0x71],
    [0x7A, 0xD1, 0x51],
    [0xBB, 0xDF, 0x27],
    [0xFD, 0xE7, 0x25],
];

/// The colour of a block of a density map that lies wholly outside the structure (no point of
/// its level-0 faces): a pale grey, off the colour map.
pub const OUTSIDE: Rgb = [0xEE, 0xEE, 0xEE];

/// The colour of density `d` (clamped to [0, 1]): dark violet for 0, teal for 1/2, yellow for 1,
/// linear between the stops.
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
    lab(c)[0]
}

/// CIE L*a*b* (D65 white) of an sRGB colour.
pub fn lab(c: Rgb) -> [f64; 3] {
    let lin = |v: u8| {
        let v = f64::from(v) / 255.0;
        if v <= 0.04045 {
            v / 12.92
        } else {
            ((v + 0.055) / 1.055).powf(2.4)
        }
    };
    let [r, g, b] = c.map(lin);
    let x = (0.4124 * r + 0.3576 * g + 0.1805 * b) / 0.95047;
    let y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
    let z = (0.0193 * r + 0.1192 * g + 0.9505 * b) / 1.08883;
    let f = |t: f64| {
        if t > 216.0 / 24389.0 {
            t.cbrt()
        } else {
            (24389.0 / 27.0 * t + 16.0) / 116.0
        }
    };
    let (fx, fy, fz) = (f(x), f(y), f(z));
    [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)]
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
    fn the_first_24_type_colours_are_pairwise_distinct() {
        // Issue #32: types 0 and 9, 3 and 12, 5 and 14 were one hue in two shades. Now every
        // pair of the first 24 is at least ΔE76 22.8 apart (Tol's own closest pair is 22.80);
        // the 25th repeats the first, darker.
        let mut least = f64::INFINITY;
        for a in 0..DISTINCT_TYPES {
            for b in a + 1..DISTINCT_TYPES {
                let (x, y) = (lab(type_colour(a)), lab(type_colour(b)));
                let d = (0..3).map(|k| (x[k] - y[k]).powi(2)).sum::<f64>().sqrt();
                least = least.min(d);
            }
        }
        assert!(
            least > 22.8,
            "two of the first 24 colours are {least} apart"
        );
        assert_eq!(DISTINCT_TYPES, 24);
        let (first, again) = (type_colour(0), type_colour(24));
        assert!((0..3).all(|k| again[k] < first[k]), "{}", hex(again));
        // White is L* 100, a* = b* = 0 (to the 4-digit matrix), black L* 0: the formulas' ends.
        let w = lab([255, 255, 255]);
        assert!((w[0] - 100.0).abs() < 0.01 && w[1].abs() < 0.05 && w[2].abs() < 0.05);
        assert!(lightness([0, 0, 0]).abs() < 1e-9);
    }

    #[test]
    fn the_density_map_is_sequential_and_outside_is_off_it() {
        assert_eq!(density_colour(0.0), [0x44, 0x01, 0x54]);
        assert_eq!(density_colour(1.0), [0xFD, 0xE7, 0x25]);
        assert_eq!(density_colour(0.5), [0x21, 0x90, 0x8C]);
        assert_eq!(density_colour(f64::NAN), density_colour(0.0));
        // Sequential: lightness grows with the density (checked on 101 values).
        let l: Vec<f64> = (0..=100)
            .map(|k| lightness(density_colour(f64::from(k) / 100.0)))
            .collect();
        assert!(l.windows(2).all(|w| w[1] > w[0]), "{l:?}");
        // Outside is lighter than any density's colour, and grey (off the map's hues).
        assert!(lightness(OUTSIDE) > l[100] + 3.0);
        assert!(OUTSIDE[0] == OUTSIDE[1] && OUTSIDE[1] == OUTSIDE[2]);
    }
}
