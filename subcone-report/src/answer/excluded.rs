//! The rows left out of the fronts (and, timed on another device, of the
//! picks): repeated images and rows timed on another device.

use subcone_scene::TimingSource;

use crate::key::{RowKey, SceneId};
use crate::named::NOAA;
use crate::ResultRow;

/// Why a row is left out of the fronts (and, [`Why::OtherDevice`], of the
/// picks).
#[derive(Clone, Debug, PartialEq)]
pub enum Why {
    /// Its image is byte-identical to `as_method`'s (same scene and
    /// backend), which comes first in table order.
    SameImage {
        /// The row it repeats.
        as_method: RowKey,
    },
    /// Part of its time was measured by `sources`, which NoAA's row of the
    /// same scene and backend (timed by `noaa`) does not use.
    OtherDevice {
        /// The row's timing sources that NoAA's row does not have.
        sources: Vec<TimingSource>,
        /// NoAA's timing sources.
        noaa: Vec<TimingSource>,
    },
}

/// A row left out of the fronts (and, timed on another device, of the
/// picks).
#[derive(Clone, Debug, PartialEq)]
pub struct Excluded {
    /// Scene.
    pub scene: SceneId,
    /// Backend.
    pub backend: String,
    /// Method.
    pub method: RowKey,
    /// Why.
    pub why: Why,
}

impl Excluded {
    /// The mark the row's method gets in tables and plots: `†` for another
    /// device, `(same image as …)` for a repeated image.
    pub fn mark(&self) -> String {
        match &self.why {
            Why::SameImage { as_method } => format!("(same image as {as_method})"),
            Why::OtherDevice { .. } => "†".into(),
        }
    }

    /// Why the row is left out, as a clause.
    pub fn reason(&self) -> String {
        match &self.why {
            Why::SameImage { as_method } => format!(
                "its image is byte-identical to {as_method}'s, so it adds no point of its own (its time is in the scene's table, and it stays a candidate for the picks)"
            ),
            Why::OtherDevice { sources, noaa } => format!(
                "part of its time is measured by {}, not by the {} every {} row without a post-process is timed by, so its time is not on their axis",
                join(sources),
                join(noaa),
                self.backend
            ),
        }
    }
}

fn join(sources: &[TimingSource]) -> String {
    sources
        .iter()
        .map(|s| s.to_string())
        .collect::<Vec<_>>()
        .join(" and ")
}

/// A hash of an 8-bit image's size and bytes, to find rows whose images are
/// byte-identical ([`ResultRow::image_digest`]).
pub fn digest(width: u32, height: u32, data: &[u8]) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::hash::DefaultHasher::new();
    (width, height, data).hash(&mut h);
    h.finish()
}

/// The rows of `rows` left out of the fronts (and, timed on another device,
/// of the picks), in row order. A group of rows with byte-identical images
/// is named after the row that every timed round tells apart as the fastest
/// (its slowest round faster than every other's fastest: a `-hybrid` beside
/// its traced twin), else after the first row of the group in table order
/// (a row timed on another device last): the name does not change with the
/// clock's noise from scene to scene, and a front never shows a point at a
/// time its image's fastest method beats in every round.
pub fn exclusions(rows: &[&ResultRow]) -> Vec<Excluded> {
    let base = |r: &ResultRow| {
        rows.iter()
            .find(|x| x.scene == r.scene && x.backend == r.backend && x.method == NOAA)
            .map(|x| x.timed_by.clone())
    };
    let other = |r: &ResultRow| -> Option<Why> {
        let noaa = base(r)?;
        let sources: Vec<TimingSource> = r
            .timed_by
            .iter()
            .filter(|s| !noaa.contains(s))
            .copied()
            .collect();
        (!sources.is_empty()).then_some(Why::OtherDevice { sources, noaa })
    };
    let mut out = Vec::new();
    for (i, r) in rows.iter().enumerate() {
        let twin = r.image_digest.and_then(|d| {
            let group: Vec<(usize, &&ResultRow)> = rows
                .iter()
                .enumerate()
                .filter(|(_, x)| {
                    x.scene == r.scene && x.backend == r.backend && x.image_digest == Some(d)
                })
                .collect();
            let clearly_fastest = group.iter().find(|(j, x)| {
                other(x).is_none()
                    && x.ms_max.is_finite()
                    && group
                        .iter()
                        .filter(|(k, _)| k != j)
                        .all(|(_, y)| x.ms_max < y.ms_min)
            });
            clearly_fastest
                .or_else(|| group.iter().min_by_key(|(j, x)| (other(x).is_some(), *j)))
                .filter(|(j, _)| *j != i)
                .map(|(_, x)| x.method.clone())
        });
        let why = match twin {
            Some(as_method) => Some(Why::SameImage { as_method }),
            None => other(r),
        };
        if let Some(why) = why {
            out.push(Excluded {
                scene: r.scene.clone(),
                backend: r.backend.clone(),
                method: r.method.clone(),
                why,
            });
        }
    }
    out
}

/// `r`'s entry in `ex`, when it is left out.
pub fn excluded<'a>(ex: &'a [Excluded], r: &ResultRow) -> Option<&'a Excluded> {
    ex.iter()
        .find(|e| e.scene == r.scene && e.backend == r.backend && e.method == r.method)
}

/// The methods whose images `r`'s repeats, for its label (`ctss (=
/// ctss-delayed)`): the rows left out as the same image as `r`.
pub fn same_image_twins(ex: &[Excluded], r: &ResultRow) -> Vec<RowKey> {
    ex.iter()
        .filter(|e| {
            e.scene == r.scene
                && e.backend == r.backend
                && matches!(&e.why, Why::SameImage { as_method } if *as_method == r.method)
        })
        .map(|e| e.method.clone())
        .collect()
}
