//! How alike two colours look, to normal vision, to the three dichromacies and in greyscale:
//! the colour as a dichromat sees it by Machado, Oliveira & Fernandes (2009, IEEE TVCG 15(6),
//! severity 1, applied to linear RGB), greyscale as the relative luminance Y, and the difference
//! by CIEDE2000 (Sharma, Wu & Dalal 2005, on CIELAB under D65). The figures' palettes
//! ([`crate::style`]) are tested with it.

/// Who looks at a figure, or how it is printed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Vision {
    Normal,
    Protanopia,
    Deuteranopia,
    Tritanopia,
    Greyscale,
}

impl Vision {
    pub const ALL: [Vision; 5] = [
        Vision::Normal,
        Vision::Protanopia,
        Vision::Deuteranopia,
        Vision::Tritanopia,
        Vision::Greyscale,
    ];
}

/// Machado et al. (2009), Table 1 at severity 1.0, on linear RGB.
const PROTANOPIA: [[f64; 3]; 3] = [
    [0.152286, 1.052583, -0.204868],
    [0.114503, 0.786281, 0.099216],
    [-0.003882, -0.048116, 1.051998],
];
const DEUTERANOPIA: [[f64; 3]; 3] = [
    [0.367322, 0.860646, -0.227968],
    [0.280085, 0.672501, 0.047413],
    [-0.011820, 0.042940, 0.968881],
];
const TRITANOPIA: [[f64; 3]; 3] = [
    [1.255528, -0.076749, -0.178779],
    [-0.078411, 0.930809, 0.147602],
    [0.004733, 0.691367, 0.303900],
];

/// An sRGB channel (0-255) in linear light.
fn linear(c: u8) -> f64 {
    let c = c as f64 / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// The linear RGB a viewer with `vision` sees for the sRGB colour `rgb` (clipped to the gamut).
pub fn seen(rgb: [u8; 3], vision: Vision) -> [f64; 3] {
    let l = rgb.map(linear);
    let m = match vision {
        Vision::Normal => return l,
        Vision::Greyscale => {
            let y = 0.2126 * l[0] + 0.7152 * l[1] + 0.0722 * l[2];
            return [y; 3];
        }
        Vision::Protanopia => PROTANOPIA,
        Vision::Deuteranopia => DEUTERANOPIA,
        Vision::Tritanopia => TRITANOPIA,
    };
    let row = |r: [f64; 3]| (r[0] * l[0] + r[1] * l[1] + r[2] * l[2]).clamp(0.0, 1.0);
    [row(m[0]), row(m[1]), row(m[2])]
}

/// CIELAB (D65) of a linear sRGB colour.
pub fn lab(l: [f64; 3]) -> [f64; 3] {
    let x = 0.4124564 * l[0] + 0.3575761 * l[1] + 0.1804375 * l[2];
    let y = 0.2126729 * l[0] + 0.7151522 * l[1] + 0.0721750 * l[2];
    let z = 0.0193339 * l[0] + 0.1191920 * l[1] + 0.9503041 * l[2];
    let f = |t: f64| {
        let d: f64 = 6.0 / 29.0;
        if t > d.powi(3) {
            t.cbrt()
        } else {
            t / (3.0 * d * d) + 4.0 / 29.0
        }
    };
    let (fx, fy, fz) = (f(x / 0.95047), f(y), f(z / 1.08883));
    [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)]
}

/// The CIEDE2000 colour difference ΔE₀₀ of two CIELAB colours (k_L = k_C = k_H = 1).
pub fn ciede2000(a: [f64; 3], b: [f64; 3]) -> f64 {
    let ([l1, a1, b1], [l2, a2, b2]) = (a, b);
    let c_bar = (a1.hypot(b1) + a2.hypot(b2)) / 2.0;
    let p7 = |c: f64| (c.powi(7) / (c.powi(7) + 25f64.powi(7))).sqrt();
    let g = 0.5 * (1.0 - p7(c_bar));
    let (a1p, a2p) = ((1.0 + g) * a1, (1.0 + g) * a2);
    let (c1, c2) = (a1p.hypot(b1), a2p.hypot(b2));
    let hue = |b: f64, a: f64| {
        if b == 0.0 && a == 0.0 {
            0.0
        } else {
            b.atan2(a).to_degrees().rem_euclid(360.0)
        }
    };
    let (h1, h2) = (hue(b1, a1p), hue(b2, a2p));
    let dl = l2 - l1;
    let dc = c2 - c1;
    let dh = if c1 * c2 == 0.0 {
        0.0
    } else if (h2 - h1).abs() <= 180.0 {
        h2 - h1
    } else if h2 - h1 > 180.0 {
        h2 - h1 - 360.0
    } else {
        h2 - h1 + 360.0
    };
    let dh_big = 2.0 * (c1 * c2).sqrt() * (dh / 2.0).to_radians().sin();
    let l_bar = (l1 + l2) / 2.0;
    let c_bar_p = (c1 + c2) / 2.0;
    let h_bar = if c1 * c2 == 0.0 {
        h1 + h2
    } else if (h1 - h2).abs() <= 180.0 {
        (h1 + h2) / 2.0
    } else if h1 + h2 < 360.0 {
        (h1 + h2 + 360.0) / 2.0
    } else {
        (h1 + h2 - 360.0) / 2.0
    };
    let cos = |deg: f64| deg.to_radians().cos();
    let t =
        1.0 - 0.17 * cos(h_bar - 30.0) + 0.24 * cos(2.0 * h_bar) + 0.32 * cos(3.0 * h_bar + 6.0)
            - 0.20 * cos(4.0 * h_bar - 63.0);
    let d_theta = 30.0 * (-((h_bar - 275.0) / 25.0).powi(2)).exp();
    let rc = 2.0 * p7(c_bar_p);
    let sl = 1.0 + 0.015 * (l_bar - 50.0).powi(2) / (20.0 + (l_bar - 50.0).powi(2)).sqrt();
    let sc = 1.0 + 0.045 * c_bar_p;
    let sh = 1.0 + 0.015 * c_bar_p * t;
    let rt = -(2.0 * d_theta).to_radians().sin() * rc;
    let (tl, tc, th) = (dl / sl, dc / sc, dh_big / sh);
    (tl * tl + tc * tc + th * th + rt * tc * th).sqrt()
}

/// ΔE₀₀ between two sRGB colours as a viewer with `vision` sees them.
pub fn difference(a: [u8; 3], b: [u8; 3], vision: Vision) -> f64 {
    ciede2000(lab(seen(a, vision)), lab(seen(b, vision)))
}

/// The smallest ΔE₀₀ over every pair of `colours` for `vision`, with the pair.
pub fn closest_pair(colours: &[[u8; 3]], vision: Vision) -> (f64, usize, usize) {
    let mut best = (f64::INFINITY, 0, 0);
    for i in 0..colours.len() {
        for j in i + 1..colours.len() {
            let d = difference(colours[i], colours[j], vision);
            if d < best.0 {
                best = (d, i, j);
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ciede2000_matches_sharmas_test_data() {
        // Sharma, Wu & Dalal (2005), Table 1: pairs 1, 7, 13, 17, 25, 34.
        let pairs = [
            ([50.0, 2.6772, -79.7751], [50.0, 0.0, -82.7485], 2.0425),
            ([50.0, 0.0, 0.0], [50.0, -1.0, 2.0], 2.3669),
            ([50.0, 2.4900, -0.0010], [50.0, -2.4900, 0.0011], 7.2195),
            ([50.0, 2.5, 0.0], [73.0, 25.0, -18.0], 27.1492),
            (
                [60.2574, -34.0099, 36.2677],
                [60.4626, -34.1751, 39.4387],
                1.2644,
            ),
            (
                [2.0776, 0.0795, -1.1350],
                [0.9033, -0.0636, -0.5514],
                0.9082,
            ),
        ];
        for (a, b, expected) in pairs {
            let d = ciede2000(a, b);
            assert!(
                (d - expected).abs() < 1e-4,
                "{a:?} {b:?}: {d} != {expected}"
            );
            assert!((ciede2000(b, a) - d).abs() < 1e-12, "symmetric");
        }
    }

    #[test]
    fn dichromats_confuse_red_and_green_and_greyscale_keeps_only_lightness() {
        // Pure red and a green of the same luminance are far apart to normal vision, close to a
        // protanope and a deuteranope, and equal in greyscale.
        let (red, green) = ([200, 40, 40], [72, 110, 40]);
        let normal = difference(red, green, Vision::Normal);
        assert!(normal > 30.0, "{normal}");
        for v in [Vision::Protanopia, Vision::Deuteranopia] {
            let d = difference(red, green, v);
            assert!(d < normal / 3.0, "{v:?}: {d}");
        }
        assert!(difference(red, green, Vision::Greyscale) < 3.0);
        // Lab of white is L = 100 at the D65 white point.
        let w = lab(seen([255, 255, 255], Vision::Normal));
        assert!(
            (w[0] - 100.0).abs() < 1e-3 && w[1].abs() < 1e-2 && w[2].abs() < 1e-2,
            "{w:?}"
        );
    }
}
