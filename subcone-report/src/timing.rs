//! Timing statistics: median and range of wall times, per-pass medians, and
//! the interleaved rounds' order and per-round ratios.
//!
//! The report times the methods of a scene and backend in *rounds*: after
//! every method's warm-up, round `r` renders each method once at the timing
//! size, starting at the method of index `r mod n` ([`round_order`]). A
//! machine's drift (another process waking up, the clock throttling) then
//! falls on every method about alike instead of on whichever method was
//! being timed at that moment, and a ratio between two methods is taken
//! within each round ([`round_ratios`]): both sides of it were measured a
//! few frames apart.

use std::time::Duration;

use subcone_scene::{Frame, TimingSource};

/// A method whose timed render is predicted (its quality render's time,
/// scaled by pixels) to take less than this also gets a warm-up render at
/// the timing size after its quality render. The first render at a new size
/// pays fixed costs (the fresh buffers' page faults, the allocator growing),
/// a few ms that a median of three would carry into a 100 ms frame but not
/// into a frame of seconds, where the extra warm-up would cost most.
pub const SHORT_RENDER: Duration = Duration::from_secs(1);

/// Whether a method gets a warm-up render at the timing size before the
/// timed rounds: always without a quality render (`quality_wall` is `None`:
/// timing only, or the quality render failed); never when the quality render
/// was at the timing size (it was the first render at that size); else when
/// its time scaled by pixels from `quality_size` to `timing_size` is under
/// [`SHORT_RENDER`] (a zero-pixel quality size counts as one pixel).
pub fn warm_up_at_timing_size(
    quality_wall: Option<Duration>,
    timing_size: (u32, u32),
    quality_size: (u32, u32),
) -> bool {
    let Some(wall) = quality_wall else {
        return true;
    };
    if quality_size == timing_size {
        return false;
    }
    let px = |(w, h): (u32, u32)| (w as f64 * h as f64).max(1.0);
    wall.as_secs_f64() * px(timing_size) / px(quality_size) < SHORT_RENDER.as_secs_f64()
}

/// Median of `v` (mean of the two middle values for an even count); `None`
/// when empty. NaNs sort last.
pub fn median(v: &[f64]) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    let mut s = v.to_vec();
    s.sort_by(|a, b| a.total_cmp(b));
    let m = s.len() / 2;
    Some(if s.len() % 2 == 1 {
        s[m]
    } else {
        (s[m - 1] + s[m]) / 2.0
    })
}

/// The order of round `round` over `n` methods (indices into the methods'
/// order): every index once, starting at `round mod n` and wrapping, so
/// the method rendered first (right after the previous round's last, or the
/// warm-ups) changes from one round to the next and each method takes each
/// position once in `n` rounds. Empty when `n` is 0.
pub fn round_order(n: usize, round: usize) -> impl Iterator<Item = usize> {
    let start = if n == 0 { 0 } else { round % n };
    (0..n).map(move |k| (start + k) % n)
}

/// The median and range of per-round ratios.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spread {
    /// Median of the per-round ratios (mean of the middle two for an even
    /// number of rounds).
    pub median: f64,
    /// Smallest per-round ratio.
    pub min: f64,
    /// Largest per-round ratio.
    pub max: f64,
}

/// The ratio of two methods timed in the same rounds: `num[r] / den[r]` for
/// each round `r`, summarised as median, min and max. `None` when the two
/// were not timed over the same number of rounds, there is no round, or a
/// round has a time that is not positive and finite (no ratio is better
/// than a wrong one).
pub fn round_ratios(num: &[f64], den: &[f64]) -> Option<Spread> {
    if num.is_empty() || num.len() != den.len() {
        return None;
    }
    let ok = |v: f64| v.is_finite() && v > 0.0;
    let ratios: Vec<f64> = num
        .iter()
        .zip(den)
        .map(|(&a, &b)| (ok(a) && ok(b)).then(|| a / b))
        .collect::<Option<_>>()?;
    Some(Spread {
        median: median(&ratios)?,
        min: ratios.iter().copied().fold(f64::INFINITY, f64::min),
        max: ratios.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    })
}

/// A pass name made safe for a column: lower case, runs of anything but ASCII
/// letters and digits turned into one `_`, no leading or trailing `_`
/// (`"cone tracing"` → `"cone_tracing"`); `"unnamed"` when nothing is left.
pub fn column_safe(name: &str) -> String {
    let mut out = String::new();
    for c in name.chars() {
        if c.is_ascii_alphanumeric() {
            out.push(c.to_ascii_lowercase());
        } else if !out.ends_with('_') {
            out.push('_');
        }
    }
    let out = out.trim_matches('_').to_string();
    if out.is_empty() {
        "unnamed".into()
    } else {
        out
    }
}

/// The timings of several runs of one method.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Timings {
    /// Wall time of each timed `Backend::render` call, in ms.
    pub wall_ms: Vec<f64>,
    /// Per pass (column-safe name, in the order first seen): the pass's time
    /// in each run that had it, in ms. Passes of the same name in one frame
    /// are added up.
    pub passes: Vec<(String, Vec<f64>)>,
    /// How the passes were timed: the distinct sources, in the order first
    /// seen.
    pub sources: Vec<TimingSource>,
}

impl Timings {
    /// Record one run.
    pub fn push(&mut self, wall: Duration, frame: &Frame) {
        self.wall_ms.push(wall.as_secs_f64() * 1e3);
        for source in frame.stats.timing_sources() {
            if !self.sources.contains(&source) {
                self.sources.push(source);
            }
        }
        let mut this: Vec<(String, f64)> = Vec::new();
        for t in &frame.stats.timings {
            let name = column_safe(t.name);
            let ms = t.time.as_secs_f64() * 1e3;
            match this.iter_mut().find(|(n, _)| *n == name) {
                Some(e) => e.1 += ms,
                None => this.push((name, ms)),
            }
        }
        for (name, ms) in this {
            match self.passes.iter_mut().find(|(n, _)| *n == name) {
                Some(e) => e.1.push(ms),
                None => self.passes.push((name, vec![ms])),
            }
        }
    }

    /// Median wall time, ms.
    pub fn median(&self) -> f64 {
        median(&self.wall_ms).unwrap_or(f64::NAN)
    }

    /// Fastest run, ms.
    pub fn min(&self) -> f64 {
        self.wall_ms.iter().copied().fold(f64::INFINITY, f64::min)
    }

    /// Slowest run, ms.
    pub fn max(&self) -> f64 {
        self.wall_ms
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Median time of each pass, ms, in the order first seen.
    pub fn pass_medians(&self) -> Vec<(String, f64)> {
        self.passes
            .iter()
            .filter_map(|(n, v)| median(v).map(|m| (n.clone(), m)))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use subcone_scene::PassTiming;

    #[test]
    fn timing_size_warm_up_only_for_short_frames() {
        let ms = Duration::from_millis;
        // No quality render: always.
        assert!(warm_up_at_timing_size(None, (1280, 720), (320, 180)));
        // 16× the pixels: 50 ms predicts 800 ms (warm up), 70 ms 1.12 s (not).
        assert!(warm_up_at_timing_size(
            Some(ms(50)),
            (1280, 720),
            (320, 180)
        ));
        assert!(!warm_up_at_timing_size(
            Some(ms(70)),
            (1280, 720),
            (320, 180)
        ));
        // Same size: the quality render was the first at the timing size.
        assert!(!warm_up_at_timing_size(Some(ms(1)), (96, 64), (96, 64)));
        // Degenerate sizes do not divide by zero.
        assert!(!warm_up_at_timing_size(Some(ms(2)), (1024, 1024), (0, 0)));
    }

    #[test]
    fn rounds_rotate() {
        for n in 1..6 {
            let rounds: Vec<Vec<usize>> = (0..2 * n + 1)
                .map(|r| round_order(n, r).collect())
                .collect();
            for (r, order) in rounds.iter().enumerate() {
                // Every method exactly once per round.
                let mut sorted = order.clone();
                sorted.sort_unstable();
                assert_eq!(sorted, (0..n).collect::<Vec<_>>(), "n {n} round {r}");
                assert_eq!(order[0], r % n, "n {n} round {r}");
            }
            for pair in rounds.windows(2).filter(|_| n > 1) {
                assert_ne!(pair[0][0], pair[1][0], "n {n}: the same first method twice");
            }
            // Each method is first exactly once in n rounds.
            let mut firsts: Vec<usize> = rounds[..n].iter().map(|o| o[0]).collect();
            firsts.sort_unstable();
            assert_eq!(firsts, (0..n).collect::<Vec<_>>());
        }
        assert_eq!(round_order(3, 1).collect::<Vec<_>>(), vec![1, 2, 0]);
        assert_eq!(round_order(0, 4).count(), 0);
    }

    #[test]
    fn ratios_are_per_round() {
        // The method takes 1.2× NoAA's time in every round while the machine
        // drifts 2× over the rounds: the per-round ratio sees no drift, the
        // ratio of medians of unequal halves would.
        let noaa = [10.0, 20.0, 15.0];
        let m = [12.0, 24.0, 18.0];
        let s = round_ratios(&m, &noaa).unwrap();
        assert!((s.median - 1.2).abs() < 1e-12 && (s.min - 1.2).abs() < 1e-12);
        assert!((s.max - 1.2).abs() < 1e-12);
        // Median, min and max of 1.1, 1.5, 1.3 (not sorted by round).
        let s = round_ratios(&[11.0, 15.0, 13.0], &[10.0; 3]).unwrap();
        assert!((s.median - 1.3).abs() < 1e-12, "{s:?}");
        assert!(
            (s.min - 1.1).abs() < 1e-12 && (s.max - 1.5).abs() < 1e-12,
            "{s:?}"
        );
        // Even count: the mean of the middle two.
        let s = round_ratios(&[1.0, 4.0, 2.0, 3.0], &[1.0; 4]).unwrap();
        assert_eq!((s.median, s.min, s.max), (2.5, 1.0, 4.0));
        // Not the same rounds, no round, or a time that is not positive.
        assert_eq!(round_ratios(&[1.0, 2.0], &[1.0]), None);
        assert_eq!(round_ratios(&[], &[]), None);
        assert_eq!(round_ratios(&[1.0, 2.0], &[1.0, 0.0]), None);
        assert_eq!(round_ratios(&[f64::NAN], &[1.0]), None);
    }

    #[test]
    fn medians() {
        assert_eq!(median(&[]), None);
        assert_eq!(median(&[3.0, 1.0, 2.0]), Some(2.0));
        assert_eq!(median(&[4.0, 1.0, 2.0, 3.0]), Some(2.5));
    }

    #[test]
    fn column_names() {
        assert_eq!(column_safe("cone tracing"), "cone_tracing");
        assert_eq!(column_safe("Sphere-Tracing (2)"), "sphere_tracing_2");
        assert_eq!(column_safe("  "), "unnamed");
    }

    #[test]
    fn pass_medians_add_repeated_names() {
        let mut t = Timings::default();
        for ms in [1u64, 3, 2] {
            let mut f = Frame::new(1, 1);
            f.stats.timings = vec![
                PassTiming::cpu("shading", Duration::from_millis(ms)),
                PassTiming::cpu("shading", Duration::from_millis(1)),
            ];
            t.push(Duration::from_millis(10 * ms), &f);
        }
        assert_eq!(t.pass_medians(), vec![("shading".to_string(), 3.0)]);
        assert_eq!((t.median(), t.min(), t.max()), (20.0, 10.0, 30.0));
    }
}
