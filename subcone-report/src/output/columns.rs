//! The columns of `results.csv` and `results.json`, and each row's cells
//! in them.

use crate::classes::{self, Metric, CLASSES};
use crate::ResultRow;

/// The columns every results file has, in order.
pub const BASE_COLUMNS: [&str; 79] = [
    "scene",
    "method",
    "backend",
    "width",
    "height",
    "runs",
    "ms_median",
    "ms_min",
    "ms_max",
    "ratio_to_noaa",
    "ratio_min",
    "ratio_max",
    "flip_mean",
    "psnr_db",
    "edge_flip_mean",
    "ssim_mean",
    "samples_per_pixel",
    "rays_per_pixel",
    "buffer_mib",
    "quality_width",
    "quality_height",
    "reference",
    "flip_silhouette",
    "flip_crease",
    "flip_shadow",
    "flip_texture",
    "flip_reflection",
    "flip_flat",
    "px_silhouette",
    "px_crease",
    "px_shadow",
    "px_texture",
    "px_reflection",
    "px_flat",
    "dssim_silhouette",
    "dssim_crease",
    "dssim_shadow",
    "dssim_texture",
    "dssim_reflection",
    "dssim_flat",
    "post_process",
    "timed_by",
    "offsets",
    "flip_min",
    "flip_max",
    "ssim_min",
    "ssim_max",
    "flip_near_edge",
    "px_near_edge",
    "dssim_near_edge",
    "flip_silhouette_min",
    "flip_silhouette_max",
    "flip_crease_min",
    "flip_crease_max",
    "flip_shadow_min",
    "flip_shadow_max",
    "flip_texture_min",
    "flip_texture_max",
    "flip_reflection_min",
    "flip_reflection_max",
    "flip_flat_min",
    "flip_flat_max",
    "flip_near_edge_min",
    "flip_near_edge_max",
    "dssim_silhouette_min",
    "dssim_silhouette_max",
    "dssim_crease_min",
    "dssim_crease_max",
    "dssim_shadow_min",
    "dssim_shadow_max",
    "dssim_texture_min",
    "dssim_texture_max",
    "dssim_reflection_min",
    "dssim_reflection_max",
    "dssim_flat_min",
    "dssim_flat_max",
    "dssim_near_edge_min",
    "dssim_near_edge_max",
    "raster_samples_per_pixel",
];

/// Every `ms_<pass>` column of `rows`, sorted.
pub fn pass_columns(rows: &[ResultRow]) -> Vec<String> {
    let mut p: Vec<String> = rows
        .iter()
        .flat_map(|r| r.pass_ms.iter().map(|(n, _)| format!("ms_{n}")))
        .collect();
    p.sort();
    p.dedup();
    p
}

/// A cell value: text, a number, or nothing.
pub(super) enum Cell {
    Text(String),
    Num(f64),
    Int(u64),
    Empty,
}

fn opt(v: Option<f64>) -> Cell {
    v.map(Cell::Num).unwrap_or(Cell::Empty)
}

pub(super) fn row_cells(r: &ResultRow, passes: &[String]) -> Vec<Cell> {
    let mut c = vec![
        Cell::Text(r.scene.to_string()),
        Cell::Text(r.method.to_string()),
        Cell::Text(r.backend.clone()),
        Cell::Int(r.width as u64),
        Cell::Int(r.height as u64),
        Cell::Int(r.runs as u64),
        Cell::Num(r.ms_median),
        Cell::Num(r.ms_min),
        Cell::Num(r.ms_max),
        opt(r.ratio_to_noaa),
        opt(r.ratio_min),
        opt(r.ratio_max),
        opt(r.flip_mean),
        opt(r.psnr_db),
        opt(r.edge_flip_mean),
        opt(r.ssim_mean),
        Cell::Num(r.samples_per_pixel),
        Cell::Num(r.rays_per_pixel),
        Cell::Num(r.buffer_mib),
        r.quality_width
            .map(|v| Cell::Int(v as u64))
            .unwrap_or(Cell::Empty),
        r.quality_height
            .map(|v| Cell::Int(v as u64))
            .unwrap_or(Cell::Empty),
        r.reference.clone().map(Cell::Text).unwrap_or(Cell::Empty),
    ];
    // flip_<class>, px_<class>, then dssim_<class>, in `classes::CLASSES`
    // order.
    for class in CLASSES {
        c.push(opt(r.classes.and_then(|k| k.mean[class.index()])));
    }
    for class in CLASSES {
        c.push(
            r.classes
                .map(|k| Cell::Int(k.px[class.index()]))
                .unwrap_or(Cell::Empty),
        );
    }
    for class in CLASSES {
        c.push(opt(r.classes_ssim.and_then(|k| k.mean[class.index()])));
    }
    c.push(
        r.post_process
            .clone()
            .map(Cell::Text)
            .unwrap_or(Cell::Empty),
    );
    c.push(Cell::Text(timed_by_tags(r)));
    let measured = !r.errors_at.is_empty();
    c.push(if measured {
        Cell::Int(r.errors_at.len() as u64)
    } else {
        Cell::Empty
    });
    for metric in Metric::ALL {
        let range = r.range(metric);
        c.push(opt(range.map(|x| x.0)));
        c.push(opt(range.map(|x| x.1)));
    }
    c.push(opt(r.classes.and_then(|k| k.near_edge)));
    c.push(
        r.classes
            .map(|k| Cell::Int(k.near_edge_px))
            .unwrap_or(Cell::Empty),
    );
    c.push(opt(r.classes_ssim.and_then(|k| k.near_edge)));
    // flip_<class>_min/_max (the band last), then dssim_'s.
    for metric in Metric::ALL {
        let at = r.class_errors_at(metric);
        let spread = at.len() > 1;
        let slots = CLASSES
            .iter()
            .map(|c| Some(c.index()))
            .chain(std::iter::once(None));
        for slot in slots {
            let range = spread
                .then(|| {
                    classes::ClassError::range(&at, |e| match slot {
                        Some(i) => e.mean[i],
                        None => e.near_edge,
                    })
                })
                .flatten();
            c.push(opt(range.map(|x| x.0)));
            c.push(opt(range.map(|x| x.1)));
        }
    }
    c.push(Cell::Num(r.raster_samples_per_pixel));
    for p in passes {
        c.push(opt(r.pass(p.trim_start_matches("ms_"))));
    }
    c
}

/// The row's timing sources as tags joined by `+` (`cpu`, `gpu-timestamps`,
/// `gpu-wall-clock`): the `timed_by` column.
fn timed_by_tags(r: &ResultRow) -> String {
    r.timed_by
        .iter()
        .map(|s| s.tag())
        .collect::<Vec<_>>()
        .join("+")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_class_has_its_three_columns() {
        for c in CLASSES {
            for col in [format!("flip_{c}"), format!("px_{c}"), format!("dssim_{c}")] {
                assert!(BASE_COLUMNS.contains(&col.as_str()), "no column {col}");
            }
        }
    }
}
