//! How much of the CPU other processes took while the report timed.
//!
//! A time is only as good as the machine was quiet while it was measured.
//! Around every scene's timed rounds the report samples Linux's counters and
//! adds up the CPU time that everything but the report spent: the machine's
//! busy time (the aggregate `cpu` line of `/proc/stat`: user, nice, system,
//! irq, softirq and steal; guest time is already inside user) minus the
//! report process's own user and system time (`/proc/self/stat`), as a share
//! of the CPU time there was (wall time × the CPUs `/proc/stat` lists). Only
//! the timed rounds count: quality renders, FLIP, references and the rest are
//! the report's own business and outside the sampled intervals.
//!
//! The load average is not used: it counts the report's own threads, which
//! fill every CPU by design. The process's own time comes from
//! `/proc/self/stat` rather than `getrusage`: the same figure (user plus
//! system time of all the process's threads, children not included), in the
//! clock ticks `/proc/stat` counts in, and readable without unsafe code,
//! which this crate forbids. Clock ticks are turned into seconds with
//! `getconf CLK_TCK`, or 100 per second (Linux's `USER_HZ` on the common
//! architectures) when that cannot be asked, which the report then says.
//!
//! Both counters advance in whole ticks (10 ms at 100 per second) and are
//! sampled by the kernel in different ways, so one short interval can come
//! out a few ticks off either way; the intervals are summed with their sign
//! and only the total is clamped at zero. On another system, or where
//! `/proc/stat` cannot be read, the figure is "not measured".

use std::time::{Duration, Instant};

use anyhow::{anyhow, bail, Context as _, Result};
use serde_json::{json, Value};

/// Above this share of the CPU taken by other processes, the report's
/// header warns that its times carry their load.
pub const WARN_SHARE: f64 = 0.05;

/// Clock ticks per second assumed when `getconf CLK_TCK` cannot be asked.
pub const ASSUMED_TICKS_PER_S: f64 = 100.0;

/// The machine's CPU counters at one moment, from `/proc/stat`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MachineTicks {
    /// Busy ticks of all CPUs together: user + nice + system + irq +
    /// softirq + steal of the aggregate `cpu` line.
    pub busy: u64,
    /// CPUs the aggregate line adds up (its `cpuN` lines).
    pub cpus: u32,
}

/// The aggregate busy ticks and the CPU count of a `/proc/stat` text.
///
/// The `cpu` line's fields are user, nice, system, idle, iowait, irq,
/// softirq, steal, guest and guest_nice; kernels before 2.6.11 stop before
/// steal, which then counts as 0. Guest time is left out: the kernel already
/// counts it in user (and guest_nice in nice).
pub fn parse_proc_stat(text: &str) -> Result<MachineTicks> {
    let line = text
        .lines()
        .find(|l| l.split_whitespace().next() == Some("cpu"))
        .ok_or_else(|| anyhow!("no aggregate `cpu` line"))?;
    let fields: Vec<u64> = line
        .split_whitespace()
        .skip(1)
        .map(|f| {
            f.parse::<u64>()
                .with_context(|| format!("`cpu` field {f:?} is not a count"))
        })
        .collect::<Result<_>>()?;
    if fields.len() < 7 {
        bail!(
            "the `cpu` line has {} fields, fewer than the 7 up to softirq",
            fields.len()
        );
    }
    let at = |i: usize| fields.get(i).copied().unwrap_or(0);
    // user, nice, system; idle (3) and iowait (4) are not busy; irq,
    // softirq, steal.
    let busy = [0, 1, 2, 5, 6, 7]
        .into_iter()
        .try_fold(0u64, |sum, i| sum.checked_add(at(i)))
        .ok_or_else(|| anyhow!("the `cpu` line's counts overflow"))?;
    let cpus = text
        .lines()
        .filter(|l| {
            l.strip_prefix("cpu")
                .is_some_and(|rest| rest.starts_with(|c: char| c.is_ascii_digit()))
        })
        .count();
    if cpus == 0 {
        bail!("no `cpuN` line");
    }
    let cpus = u32::try_from(cpus).map_err(|_| anyhow!("{cpus} CPUs"))?;
    Ok(MachineTicks { busy, cpus })
}

/// User plus system ticks of a `/proc/<pid>/stat` text (fields 14 and 15,
/// every thread of the process, children not included).
///
/// The command name (field 2) is in parentheses and may hold spaces and
/// parentheses itself, so fields are counted from the last `)`.
pub fn parse_self_stat(text: &str) -> Result<u64> {
    let (_, rest) = text
        .rsplit_once(')')
        .ok_or_else(|| anyhow!("no `)` closing the command name"))?;
    // After the name: state is field 3, so utime (14) is the 12th, stime
    // (15) the 13th.
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let tick = |i: usize, name: &str| -> Result<u64> {
        let f = fields
            .get(i)
            .ok_or_else(|| anyhow!("no {name} field ({} fields)", fields.len()))?;
        f.parse::<u64>()
            .with_context(|| format!("{name} {f:?} is not a count"))
    };
    tick(11, "utime")?
        .checked_add(tick(12, "stime")?)
        .ok_or_else(|| anyhow!("utime + stime overflow"))
}

/// Clock ticks per second of `/proc/stat`, and whether it was assumed.
fn ticks_per_s() -> (f64, bool) {
    std::process::Command::new("getconf")
        .arg("CLK_TCK")
        .output()
        .ok()
        .filter(|o| o.status.success())
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .and_then(|s| s.trim().parse::<f64>().ok())
        .filter(|&t| t.is_finite() && t >= 1.0)
        .map_or((ASSUMED_TICKS_PER_S, true), |t| (t, false))
}

/// The counters at the start of a timed interval.
#[derive(Clone, Copy, Debug)]
pub struct Sample {
    at: Instant,
    machine: MachineTicks,
    own: u64,
}

/// Reads both counters now; the reason when they cannot be read.
fn sample() -> Result<Sample> {
    let stat = std::fs::read_to_string("/proc/stat").context("/proc/stat")?;
    let own = std::fs::read_to_string("/proc/self/stat").context("/proc/self/stat")?;
    let own = parse_self_stat(&own).context("/proc/self/stat")?;
    let machine = parse_proc_stat(&stat).context("/proc/stat")?;
    Ok(Sample {
        at: Instant::now(),
        machine,
        own,
    })
}

/// The other processes' CPU time over the intervals measured so far.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct OtherCpu {
    /// Clock ticks per second, and whether assumed (set at the first
    /// readable sample).
    ticks_per_s: Option<(f64, bool)>,
    /// Busy ticks of the machine minus the report's own, summed with their
    /// sign over the intervals.
    other_ticks: i64,
    /// The report's own ticks over the intervals.
    own_ticks: u64,
    /// Wall time × CPUs over the intervals, s.
    available_s: f64,
    /// Wall time of the intervals, s.
    wall_s: f64,
    /// Intervals measured.
    measured: u32,
    /// Intervals not measured, and the last reason.
    unmeasured: u32,
    reason: Option<String>,
}

impl OtherCpu {
    /// Start a timed interval: the counters now, or `None` (and the reason
    /// kept) where they cannot be read. Call right before the first timed
    /// render; it asks the clock tick rate once, before the counters.
    pub fn start(&mut self) -> Option<Sample> {
        if self.ticks_per_s.is_none() && std::path::Path::new("/proc/stat").exists() {
            self.ticks_per_s = Some(ticks_per_s());
        }
        match sample() {
            Ok(s) => Some(s),
            Err(e) => {
                self.reason = Some(format!("{e:#}"));
                None
            }
        }
    }

    /// End the interval begun by `start` (right after the last timed
    /// render) and add it up.
    pub fn stop(&mut self, start: Option<Sample>) {
        let end = sample();
        match (start, end) {
            (Some(a), Ok(b)) => self.add(&a, &b),
            (_, Err(e)) => {
                self.reason = Some(format!("{e:#}"));
                self.unmeasured += 1;
            }
            (None, _) => self.unmeasured += 1,
        }
    }

    /// Add the interval from `a` to `b`.
    fn add(&mut self, a: &Sample, b: &Sample) {
        let wall = b.at.saturating_duration_since(a.at);
        self.add_ticks(a.machine, b.machine, b.own as i64 - a.own as i64, wall);
    }

    /// Add an interval of `wall` over which the machine went from `a` to `b`
    /// and the report spent `own` ticks. Counters that went backwards (a
    /// reset, another boot's file) make the interval unmeasured.
    fn add_ticks(&mut self, a: MachineTicks, b: MachineTicks, own: i64, wall: Duration) {
        let Some(busy) = b.busy.checked_sub(a.busy) else {
            self.unmeasured += 1;
            self.reason = Some("the /proc/stat counters went backwards".into());
            return;
        };
        if own < 0 {
            self.unmeasured += 1;
            self.reason = Some("the process's CPU time went backwards".into());
            return;
        }
        let busy = i64::try_from(busy).unwrap_or(i64::MAX);
        self.other_ticks = self.other_ticks.saturating_add(busy - own);
        self.own_ticks = self.own_ticks.saturating_add(own as u64);
        self.wall_s += wall.as_secs_f64();
        self.available_s += wall.as_secs_f64() * a.cpus.min(b.cpus) as f64;
        self.measured += 1;
    }

    /// Other processes' CPU time over the measured intervals, s (clamped
    /// at 0: a few ticks of sampling error can make it negative).
    pub fn other_s(&self) -> Option<f64> {
        let (tps, _) = self.ticks_per_s?;
        (self.measured > 0).then(|| self.other_ticks.max(0) as f64 / tps)
    }

    /// The report's own CPU time over the measured intervals, s.
    pub fn own_s(&self) -> Option<f64> {
        let (tps, _) = self.ticks_per_s?;
        (self.measured > 0).then(|| self.own_ticks as f64 / tps)
    }

    /// The share of the available CPU time (wall × CPUs) that other
    /// processes took; `None` when nothing was measured.
    pub fn share(&self) -> Option<f64> {
        let other = self.other_s()?;
        (self.available_s > 0.0).then(|| other / self.available_s)
    }

    /// The header's sentence: the share, what it is of, and how it was
    /// measured, or why it was not.
    pub fn sentence(&self) -> String {
        let Some(share) = self.share() else {
            return format!(
                "Other processes' CPU time during the timed rounds: not measured ({}).",
                match &self.reason {
                    Some(r) => r.clone(),
                    None if self.measured + self.unmeasured == 0 => "no timed round ran".into(),
                    None => "no interval to measure".into(),
                }
            );
        };
        let (tps, assumed) = self.ticks_per_s.unwrap_or((ASSUMED_TICKS_PER_S, true));
        let mut s = format!(
            "Other processes took {:.1} % of the CPU during the timed rounds ({:.2} of {:.2} CPU·s \
over {:.2} s of rounds; the report itself took {:.2} CPU·s), from /proc/stat",
            100.0 * share,
            self.other_s().unwrap_or(0.0),
            self.available_s,
            self.wall_s,
            self.own_s().unwrap_or(0.0),
        );
        if assumed {
            s.push_str(&format!(
                ", assuming {tps:.0} clock ticks per second (getconf CLK_TCK did not answer)"
            ));
        }
        if self.unmeasured > 0 {
            s.push_str(&format!(
                "; {} of {} intervals not measured",
                self.unmeasured,
                self.unmeasured + self.measured
            ));
        }
        s.push('.');
        s
    }

    /// A warning when other processes took more than [`WARN_SHARE`].
    pub fn warning(&self) -> Option<String> {
        let share = self.share().filter(|&s| s > WARN_SHARE)?;
        Some(format!(
            "**Warning: other processes took {:.1} % of the CPU during the timed rounds** (more \
than {:.0} %): the times carry their load, and the ratios to NoAA, taken within each \
round, cancel only the part of it that was steady over a round.",
            100.0 * share,
            100.0 * WARN_SHARE
        ))
    }

    /// `results.json`'s record of it: the figures, or `measured: false`
    /// and the reason.
    pub fn json(&self) -> Value {
        let Some(share) = self.share() else {
            return json!({ "measured": false, "reason": self.reason });
        };
        let (tps, assumed) = self.ticks_per_s.unwrap_or((ASSUMED_TICKS_PER_S, true));
        json!({
            "measured": true,
            "share": share,
            "other_cpu_s": self.other_s(),
            "own_cpu_s": self.own_s(),
            "available_cpu_s": self.available_s,
            "rounds_wall_s": self.wall_s,
            "ticks_per_s": tps,
            "ticks_per_s_assumed": assumed,
            "intervals": self.measured,
            "intervals_unmeasured": self.unmeasured,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const STAT: &str = "\
cpu  69754 3 4715 98074 178 11 29 13 500 7
cpu0 34850 1 2169 49304 47 5 5 7 250 3
cpu1 34903 2 2545 48769 130 6 24 5 250 4
intr 1234 0 0
ctxt 5678
btime 1700000000
processes 8848
procs_running 3
";

    #[test]
    fn proc_stat_busy_leaves_out_idle_iowait_and_guest() {
        let t = parse_proc_stat(STAT).unwrap();
        // user + nice + system + irq + softirq + steal; not idle (98074),
        // iowait (178), guest (500) or guest_nice (7).
        assert_eq!(t.busy, 69754 + 3 + 4715 + 11 + 29 + 13);
        assert_eq!(t.cpus, 2);
    }

    #[test]
    fn proc_stat_before_steal_and_bad_text() {
        // A kernel without steal: 7 fields.
        let old = "cpu 10 0 5 100 1 2 3\ncpu0 10 0 5 100 1 2 3\n";
        assert_eq!(
            parse_proc_stat(old).unwrap(),
            MachineTicks { busy: 20, cpus: 1 }
        );
        assert!(parse_proc_stat("").is_err());
        // `cpu0` alone is not the aggregate line.
        assert!(parse_proc_stat("cpu0 1 2 3 4 5 6 7 8\n").is_err());
        assert!(parse_proc_stat("cpu 1 2 3 4 5 6\ncpu0 1 2 3 4 5 6\n").is_err());
        assert!(parse_proc_stat("cpu 1 2 x 4 5 6 7 8\ncpu0 1 2 3 4 5 6 7 8\n").is_err());
        // An aggregate line without per-CPU lines gives no CPU count.
        assert!(parse_proc_stat("cpu 1 2 3 4 5 6 7 8\n").is_err());
        let max = format!("cpu {} 1 0 0 0 0 0 0\ncpu0 1 1 1 1 1 1 1 1\n", u64::MAX);
        assert!(parse_proc_stat(&max).is_err());
    }

    #[test]
    fn self_stat_counts_from_the_last_parenthesis() {
        // A command name with spaces and parentheses; utime 1200, stime 34.
        let text = "4242 (sub (cone) x) R 1 4242 4242 0 -1 4194304 9000 0 0 0 1200 34 0 0 20 0 9 0 100 0 0";
        assert_eq!(parse_self_stat(text).unwrap(), 1234);
        assert!(parse_self_stat("4242 subcone R 1 2").is_err());
        assert!(parse_self_stat("4242 (subcone) R 1 2 3").is_err());
        assert!(parse_self_stat("1 (a) R 1 1 1 0 -1 0 0 0 0 0 x 34").is_err());
    }

    #[test]
    fn share_of_wall_times_cpus_less_own_time() {
        let mut l = OtherCpu {
            ticks_per_s: Some((100.0, false)),
            ..Default::default()
        };
        assert_eq!(l.share(), None);
        assert!(l.sentence().contains("not measured (no timed round ran)"));
        let m = |busy| MachineTicks { busy, cpus: 2 };
        // 10 s on 2 CPUs: 2000 ticks available; the machine was busy 1900,
        // the report 1800 of them: others 100 ticks = 1 s = 5 %.
        l.add_ticks(m(1000), m(2900), 1800, Duration::from_secs(10));
        assert!((l.share().unwrap() - 0.05).abs() < 1e-12);
        assert!(l.warning().is_none(), "5 % is not above 5 %");
        // Another 10 s where others took 300 ticks: 400 of 4000 = 10 %.
        l.add_ticks(m(2900), m(4900), 1700, Duration::from_secs(10));
        assert!((l.share().unwrap() - 0.10).abs() < 1e-12);
        assert!(l.warning().unwrap().contains("10.0 %"));
        assert!(l
            .sentence()
            .starts_with("Other processes took 10.0 % of the CPU"));
        // A negative interval (sampling error) is summed with its sign.
        l.add_ticks(m(4900), m(5000), 150, Duration::from_secs(1));
        assert!((l.other_s().unwrap() - 3.5).abs() < 1e-12);
        // Counters that went backwards are not measured, and said so.
        l.add_ticks(m(5000), m(10), 0, Duration::from_secs(1));
        assert!(l.sentence().contains("1 of 4 intervals not measured"));
        assert_eq!(l.json()["intervals"], json!(3));
    }

    #[test]
    fn clamped_at_zero_and_assumed_rate_said() {
        let mut l = OtherCpu {
            ticks_per_s: Some((ASSUMED_TICKS_PER_S, true)),
            ..Default::default()
        };
        let m = |busy| MachineTicks { busy, cpus: 4 };
        l.add_ticks(m(0), m(100), 120, Duration::from_secs(1));
        assert_eq!(l.share(), Some(0.0));
        assert!(l.sentence().contains("assuming 100 clock ticks per second"));
    }
}
