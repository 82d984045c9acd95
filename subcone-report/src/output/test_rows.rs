//! Rows for the tests of the output files.

use crate::classes::{self, Class};
use crate::ResultRow;

pub(super) fn row(method: &str, passes: &[(&str, f64)]) -> ResultRow {
    ResultRow {
        scene: crate::key::SceneId::new("s,1"),
        method: crate::key::named(method),
        backend: "cpu".into(),
        width: 4,
        height: 2,
        runs: 3,
        ms_median: 2.5,
        ms_min: 2.0,
        ms_max: 3.0,
        ratio_to_noaa: None,
        ratio_min: None,
        ratio_max: None,
        flip_mean: Some(0.125),
        psnr_db: Some(f64::INFINITY),
        edge_flip_mean: None,
        classes: None,
        ssim_mean: None,
        classes_ssim: None,
        errors_at: Vec::new(),
        samples_per_pixel: 1.0,
        rays_per_pixel: 2.0,
        raster_samples_per_pixel: 0.0,
        buffer_mib: 0.5,
        quality_width: Some(4),
        quality_height: Some(2),
        reference: Some("ssaa64".into()),
        pass_ms: passes.iter().map(|(n, v)| (n.to_string(), *v)).collect(),
        round_ms: Vec::new(),
        post_process: None,
        timed_by: vec![subcone_scene::TimingSource::Cpu],
        image_digest: None,
    }
}

pub(super) fn ratio(mut r: ResultRow, median: f64, range: Option<(f64, f64)>) -> ResultRow {
    r.ratio_to_noaa = Some(median);
    (r.ratio_min, r.ratio_max) = (range.map(|r| r.0), range.map(|r| r.1));
    r
}

/// A row measured at four offsets: per offset `k`, FLIP `flip[k]` on
/// silhouette, `flat[k]` on flat and `band[k]` on the near-edge band,
/// and 1 − SSIM `dssim[k]` on silhouette and flat; 100 pixels in each
/// (300 flat).
pub(super) fn measured(
    method: &str,
    flip: [f64; 4],
    flat: [f64; 4],
    band: [f64; 4],
    dssim: [f64; 4],
) -> ResultRow {
    let mut r = row(method, &[]);
    r.scene = crate::key::SceneId::new("s");
    let err = |sil: f64, fl: f64, ne: Option<f64>| {
        let mut e = classes::ClassError::default();
        e.mean[Class::Silhouette.index()] = Some(sil);
        e.px[Class::Silhouette.index()] = 100;
        e.mean[Class::Flat.index()] = Some(fl);
        e.px[Class::Flat.index()] = 300;
        (e.near_edge, e.near_edge_px) = (ne, 100);
        e
    };
    r.errors_at = (0..4)
        .map(|k| crate::OffsetError {
            offset: crate::offsets::ERROR_OFFSETS[k],
            flip: flip[k],
            ssim: 1.0 - dssim[k],
            classes: err(flip[k], flat[k], Some(band[k])),
            classes_ssim: err(dssim[k], dssim[k], None),
        })
        .collect();
    r.settle_offsets();
    r
}
