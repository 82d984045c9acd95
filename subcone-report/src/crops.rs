//! Zoomed crops of the regions where antialiasing matters, chosen
//! automatically, laid side by side (NoAA | methods… | reference) like the
//! papers' comparison figures.
//!
//! All three regions are square windows of [`window_side`] pixels found by an
//! exhaustive search over every position (summed-area tables, so linear in
//! the image size):
//!
//! - **edge**: the window with the most edge-mask pixels (geometric
//!   discontinuities of the NoAA AOVs count 1, strong reference gradients
//!   only 1/4, so silhouettes win over minified textures), ties broken by the
//!   NoAA error in it;
//! - **shadow**: the window with the most NoAA error (|NoAA − reference|
//!   luminance) on *shadow-boundary pixels*: pixels that are geometrically
//!   smooth but where an untextured, reflection-free NoAA render of the scene
//!   (every albedo a flat grey, so texture edges vanish) has a strong
//!   gradient: what is left is light and shadow. Without lights, or when no
//!   such pixel exists, the NoAA error on geometrically smooth, non-reflective
//!   pixels;
//! - **reflection**: the window with the most NoAA error on *reflective
//!   pixels* (those whose NoAA colour changes when reflections are turned off,
//!   `reflection_depth = 0`), leaving out geometric edges. Without reflective
//!   pixels, the window with the most NoAA error outside the edge mask that
//!   does not overlap the shadow window.

use anyhow::{bail, Result};

use subcone_metrics::Rgb8;

/// The region kinds, in output order.
pub const KINDS: [&str; 3] = ["edge", "shadow", "reflection"];

/// Nearest-neighbour zoom of crops.
pub const ZOOM: u32 = 8;

/// A square window.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Window {
    /// Left column.
    pub x: u32,
    /// Top row.
    pub y: u32,
    /// Side in pixels.
    pub side: u32,
}

impl Window {
    /// Whether two windows overlap.
    pub fn overlaps(&self, o: &Window) -> bool {
        self.x < o.x + o.side
            && o.x < self.x + self.side
            && self.y < o.y + o.side
            && o.y < self.y + self.side
    }
}

/// Side of the crop windows for a `w × h` image: a quarter of the short side,
/// between 8 and 32 pixels (16 at 96×64, 32 from 128 pixels up).
pub fn window_side(w: u32, h: u32) -> u32 {
    (w.min(h) / 4).clamp(8, 32).min(w.min(h)).max(1)
}

/// Summed-area table of a `w × h` score image, `(w + 1) × (h + 1)`.
fn integral(score: &[f64], w: usize, h: usize) -> Vec<f64> {
    let mut s = vec![0.0; (w + 1) * (h + 1)];
    for y in 0..h {
        let mut row = 0.0;
        for x in 0..w {
            row += score[y * w + x];
            s[(y + 1) * (w + 1) + x + 1] = s[y * (w + 1) + x + 1] + row;
        }
    }
    s
}

/// The window of side `side` with the largest sum of `score`, skipping windows
/// that `exclude` rejects; `None` if every window is excluded or the image is
/// smaller than the window. The first maximum in row-major order wins.
pub fn best_window(
    score: &[f64],
    w: u32,
    h: u32,
    side: u32,
    exclude: impl Fn(&Window) -> bool,
) -> Option<(Window, f64)> {
    let (wu, hu, s) = (w as usize, h as usize, side as usize);
    if score.len() != wu * hu || s == 0 || s > wu || s > hu {
        return None;
    }
    let t = integral(score, wu, hu);
    let at = |x: usize, y: usize| t[y * (wu + 1) + x];
    let mut best: Option<(Window, f64)> = None;
    for y in 0..=hu - s {
        for x in 0..=wu - s {
            let v = at(x + s, y + s) - at(x, y + s) - at(x + s, y) + at(x, y);
            let win = Window {
                x: x as u32,
                y: y as u32,
                side,
            };
            if best.is_none_or(|(_, b)| v > b + 1e-12) && !exclude(&win) {
                best = Some((win, v));
            }
        }
    }
    best
}

/// What the region heuristics look at, all per pixel of the quality size.
pub struct RegionInputs<'a> {
    /// Width.
    pub width: u32,
    /// Height.
    pub height: u32,
    /// Edge mask (geometric or strong reference gradient).
    pub edges: &'a [bool],
    /// Geometric edges only.
    pub geometric: &'a [bool],
    /// |NoAA − reference| luminance.
    pub noaa_error: &'a [f32],
    /// Shadow-boundary candidates (see the module docs), if any could be found.
    pub shadow: Option<&'a [bool]>,
    /// Reflective pixels, if the scene has reflections.
    pub reflective: Option<&'a [bool]>,
}

/// A chosen region with the rule that chose it.
#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    /// `edge`, `shadow` or `reflection`.
    pub kind: &'static str,
    /// The window.
    pub window: Window,
    /// Which rule picked it (for report.md).
    pub rule: &'static str,
}

/// Choose the edge, shadow and reflection windows.
pub fn choose_regions(r: &RegionInputs<'_>) -> Result<Vec<Region>> {
    let n = r.width as usize * r.height as usize;
    let lens = [r.edges.len(), r.geometric.len(), r.noaa_error.len()];
    if lens.iter().any(|&l| l != n)
        || r.shadow.is_some_and(|m| m.len() != n)
        || r.reflective.is_some_and(|m| m.len() != n)
    {
        bail!("region inputs do not match the image size");
    }
    let c = RegionSearch {
        r,
        n,
        side: window_side(r.width, r.height),
    };
    let mut out = Vec::new();
    if let Some(w) = c.edge_window() {
        out.push(Region {
            kind: "edge",
            window: w,
            rule: "most edge-mask pixels (geometric edges count 4× gradient-only ones)",
        });
    }

    // Reflection on reflective pixels first, so the shadow window can avoid it.
    let mut reflection = c.reflective_window();
    let rw = reflection.map(|r: (Window, &str)| r.0);
    let away = |w: &Window| rw.is_some_and(|r| r.overlaps(w));

    let mut shadow = c.shadow_boundary_window(&away);
    if shadow.is_none() {
        shadow = c.smooth_window(&away);
    }
    if let Some((w, rule)) = shadow {
        out.push(Region {
            kind: "shadow",
            window: w,
            rule,
        });
    }

    if reflection.is_none() {
        reflection = c.off_edge_window(shadow.map(|s| s.0));
    }
    if let Some((w, rule)) = reflection {
        out.push(Region {
            kind: "reflection",
            window: w,
            rule,
        });
    }
    Ok(out)
}

/// A window found by one of the region heuristics, with the rule that
/// found it.
type Found = (Window, &'static str);

/// The searches of [`choose_regions`] over inputs already checked to hold
/// `n` pixels each, every window `side` pixels square.
struct RegionSearch<'r, 'a> {
    r: &'r RegionInputs<'a>,
    n: usize,
    side: u32,
}

impl RegionSearch<'_, '_> {
    /// NoAA's error at pixel `i`.
    fn err(&self, i: usize) -> f64 {
        self.r.noaa_error[i] as f64
    }

    /// Whether pixel `i` is reflective (never, without a reflection mask).
    fn reflective(&self, i: usize) -> bool {
        self.r.reflective.is_some_and(|m| m[i])
    }

    /// The best window for `score`, any position allowed.
    fn best(&self, score: &[f64]) -> Option<(Window, f64)> {
        best_window(score, self.r.width, self.r.height, self.side, |_| false)
    }

    /// Prefer a window that does not overlap `avoid`; take any if none is left.
    fn pick(&self, score: &[f64], avoid: &dyn Fn(&Window) -> bool) -> Option<(Window, f64)> {
        best_window(score, self.r.width, self.r.height, self.side, avoid)
            .or_else(|| self.best(score))
    }

    /// The edge window: the most edge-mask pixels, ties broken by NoAA's
    /// error.
    fn edge_window(&self) -> Option<Window> {
        let r = self.r;
        // Geometric edges count 4× gradient-only ones (texture, shadow edges), so
        // the window shows silhouettes rather than a minified texture.
        let score: Vec<f64> = (0..self.n)
            .map(|i| {
                let e = if r.geometric[i] {
                    1.0
                } else if r.edges[i] {
                    0.25
                } else {
                    0.0
                };
                e + 1e-3 * self.err(i)
            })
            .collect();
        self.best(&score).map(|(w, _)| w)
    }

    /// The reflection window on reflective pixels off geometric edges;
    /// `None` when the scene has none.
    fn reflective_window(&self) -> Option<Found> {
        let m = self.r.reflective?;
        if !m.iter().any(|&c| c) {
            return None;
        }
        let score: Vec<f64> = (0..self.n)
            .map(|i| {
                if m[i] && !self.r.geometric[i] {
                    self.err(i) + 0.02
                } else {
                    0.0
                }
            })
            .collect();
        self.best(&score)
            .map(|(w, _)| (w, "most NoAA error on reflective pixels"))
    }

    /// The shadow window on the shadow-boundary candidates that are not
    /// reflective, away from `away` if it can be; `None` without such a
    /// candidate.
    fn shadow_boundary_window(&self, away: &dyn Fn(&Window) -> bool) -> Option<Found> {
        let cand = self.r.shadow?;
        if !cand.iter().any(|&c| c) {
            return None;
        }
        let score: Vec<f64> = (0..self.n)
            .map(|i| {
                if cand[i] && !self.reflective(i) {
                    self.err(i) + 0.02
                } else {
                    0.0
                }
            })
            .collect();
        if !score.iter().any(|&v| v > 0.0) {
            return None;
        }
        self.pick(&score, away).map(|(w, _)| {
            (
                w,
                "most NoAA error on shadow boundaries (untextured render)",
            )
        })
    }

    /// The shadow window without boundary candidates: NoAA's error on
    /// geometrically smooth, non-reflective pixels, away from `away` if it
    /// can be.
    fn smooth_window(&self, away: &dyn Fn(&Window) -> bool) -> Option<Found> {
        let r = self.r;
        let score: Vec<f64> = (0..self.n)
            .map(|i| {
                if r.geometric[i] || self.reflective(i) {
                    0.0
                } else {
                    self.err(i)
                }
            })
            .collect();
        self.pick(&score, away)
            .map(|(w, _)| (w, "most NoAA error on smooth, non-reflective geometry"))
    }

    /// The reflection window of a scene without reflective pixels: NoAA's
    /// error off the edge mask, not overlapping the shadow window `sw` if
    /// it can be.
    fn off_edge_window(&self, sw: Option<Window>) -> Option<Found> {
        let score: Vec<f64> = (0..self.n)
            .map(|i| if self.r.edges[i] { 0.0 } else { self.err(i) })
            .collect();
        self.pick(&score, &|w: &Window| sw.is_some_and(|s| s.overlaps(w)))
            .map(|(w, _)| {
                (
                    w,
                    "no reflective pixels: most NoAA error off the edge mask, away from the shadow window",
                )
            })
    }
}

/// The window of `image`, zoomed `ZOOM`× nearest-neighbour.
pub fn zoom(image: &Rgb8, w: &Window) -> Result<Rgb8> {
    if w.x + w.side > image.width || w.y + w.side > image.height {
        bail!("crop window outside the image");
    }
    let side = w.side * ZOOM;
    let mut data = Vec::with_capacity((side * side * 3) as usize);
    for y in 0..side {
        for x in 0..side {
            let sx = w.x + x / ZOOM;
            let sy = w.y + y / ZOOM;
            let i = ((sy * image.width + sx) * 3) as usize;
            data.extend_from_slice(&image.data[i..i + 3]);
        }
    }
    Ok(Rgb8 {
        width: side,
        height: side,
        data,
    })
}

/// `image` enlarged (nearest neighbour) to at least 512 pixels wide, with
/// `regions` outlined, one colour per kind (edge red, shadow green,
/// reflection blue).
pub fn outline(image: &Rgb8, regions: &[Region]) -> Rgb8 {
    let k = (512 / image.width.max(1)).clamp(1, 8);
    let (w, h) = (image.width * k, image.height * k);
    let mut out = Rgb8 {
        width: w,
        height: h,
        data: Vec::with_capacity((w * h * 3) as usize),
    };
    for y in 0..h {
        for x in 0..w {
            let i = (((y / k) * image.width + x / k) * 3) as usize;
            out.data.extend_from_slice(&image.data[i..i + 3]);
        }
    }
    let colours = [[255u8, 40, 40], [40, 220, 40], [60, 120, 255]];
    let thick = k.clamp(2, 3);
    for r in regions {
        let c = colours[KINDS.iter().position(|kd| *kd == r.kind).unwrap_or(0) % 3];
        let (x0, y0, s) = (r.window.x * k, r.window.y * k, r.window.side * k);
        for y in y0..(y0 + s).min(h) {
            for x in x0..(x0 + s).min(w) {
                let border =
                    x < x0 + thick || y < y0 + thick || x + thick >= x0 + s || y + thick >= y0 + s;
                if border {
                    let i = ((y * w + x) * 3) as usize;
                    out.data[i..i + 3].copy_from_slice(&c);
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn best_window_finds_the_hot_spot() {
        let (w, h) = (20u32, 12u32);
        let mut s = vec![0.0; (w * h) as usize];
        for y in 5..9 {
            for x in 11..15 {
                s[(y * w + x) as usize] = 1.0;
            }
        }
        let (win, v) = best_window(&s, w, h, 4, |_| false).unwrap();
        assert_eq!((win.x, win.y, v), (11, 5, 16.0));
        let (other, _) = best_window(&s, w, h, 4, |x| x.overlaps(&win)).unwrap();
        assert!(!other.overlaps(&win));
        assert!(best_window(&s, w, h, 13, |_| false).is_none());
    }

    #[test]
    fn regions_without_shadow_or_reflection_data() {
        let (w, h) = (40u32, 32u32);
        let n = (w * h) as usize;
        let mut edges = vec![false; n];
        for y in 0..h {
            edges[(y * w + 30) as usize] = true;
        }
        let err: Vec<f32> = (0..n)
            .map(|i| if i % w as usize == 5 { 1.0 } else { 0.0 })
            .collect();
        let r = choose_regions(&RegionInputs {
            width: w,
            height: h,
            edges: &edges,
            geometric: &edges,
            noaa_error: &err,
            shadow: None,
            reflective: None,
        })
        .unwrap();
        assert_eq!(r.len(), 3);
        assert!(r[0].window.x <= 30 && r[0].window.x + r[0].window.side > 30);
        assert!(r[1].window.x <= 5 && r[1].window.x + 8 > 5);
        assert!(!r[2].window.overlaps(&r[1].window));
    }

    #[test]
    fn zoom_is_nearest_neighbour() {
        let img = Rgb8 {
            width: 2,
            height: 2,
            data: vec![1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4, 4],
        };
        let z = zoom(
            &img,
            &Window {
                x: 1,
                y: 0,
                side: 1,
            },
        )
        .unwrap();
        assert_eq!(z.width, ZOOM);
        assert!(z.data.iter().all(|&v| v == 2));
        assert!(zoom(
            &img,
            &Window {
                x: 1,
                y: 1,
                side: 2
            }
        )
        .is_err());
    }
}
