//! `results.csv`.

use super::columns::{pass_columns, row_cells, Cell, BASE_COLUMNS};
use crate::ResultRow;

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

fn csv_num(v: f64) -> String {
    if v.is_nan() {
        String::new()
    } else if v.is_infinite() {
        if v > 0.0 { "inf" } else { "-inf" }.into()
    } else {
        // Round-trippable and short.
        let s = format!("{v:.6}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        if s.is_empty() || s == "-" {
            "0".into()
        } else {
            s.to_string()
        }
    }
}

/// `results.csv` of `rows`.
pub fn csv(rows: &[ResultRow]) -> String {
    let passes = pass_columns(rows);
    let mut out = BASE_COLUMNS.join(",");
    for p in &passes {
        out.push(',');
        out.push_str(p);
    }
    out.push('\n');
    for r in rows {
        let cells: Vec<String> = row_cells(r, &passes)
            .into_iter()
            .map(|c| match c {
                Cell::Text(s) => csv_field(&s),
                Cell::Num(v) => csv_num(v),
                Cell::Int(v) => v.to_string(),
                Cell::Empty => String::new(),
            })
            .collect();
        out.push_str(&cells.join(","));
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::test_rows::{ratio, row};

    #[test]
    fn csv_columns_are_stable_and_passes_sorted() {
        let rows = vec![
            row("noaa", &[("shading", 1.0)]),
            ratio(
                row("sraa", &[("shading", 1.0), ("geometry", 0.5)]),
                1.2,
                Some((1.1, 1.3)),
            ),
        ];
        let text = csv(&rows);
        let mut lines = text.lines();
        let header = lines.next().unwrap();
        assert!(header.starts_with("scene,method,backend,width,height,runs,ms_median"));
        assert!(header.contains(",dssim_flat,post_process,timed_by,offsets,flip_min,"));
        assert!(header.ends_with(
            ",dssim_near_edge_min,dssim_near_edge_max,raster_samples_per_pixel,ms_geometry,ms_shading"
        ));
        assert!(header.contains(",ms_max,ratio_to_noaa,ratio_min,ratio_max,flip_mean,"));
        let first = lines.next().unwrap();
        // No ratios, no SSIM, no classes (18 empty columns), no post-process
        // adapter: 19 empty fields between the reference and the timing
        // source; no offsets; no rasterised sample (a traced method); then
        // no geometry pass, and the shading pass.
        let expected = format!(
            "\"s,1\",noaa,cpu,4,2,3,2.5,2,3,,,,0.125,inf,,,1,2,0.5,4,2,ssaa64{}cpu{}0,,1",
            ",".repeat(20),
            ",".repeat(BASE_COLUMNS.len() - 42)
        );
        assert_eq!(first, expected);
        let second = lines.next().unwrap();
        assert!(second.contains(",2.5,2,3,1.2,1.1,1.3,0.125,"), "{second}");
    }
}
