//! What `vct bench --accuracy` writes: the summary's Markdown tables, accuracy.json and .csv,
//! the FLIP maps and indirect-light pairs, and the speed-against-accuracy charts.

use std::path::{Path, PathBuf};

use super::{region_log_error, region_log_error_text, AccuracyRow};
use crate::bench::charts;
use crate::error::{Error, Result};

/// Markdown tables of the rows: the summary per scene and variant, then each row's regions.
pub fn summary(rows: &[AccuracyRow]) -> String {
    let mut s = String::from(
        "| scene | variant | N | bounces | frame ms | memory MiB | FLIP | direct-only FLIP | FLIP / direct-only | mean / reference | regions' \\|ln ratio\\| | reference noise |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let regions = region_log_error_text(&r.regions);
        s.push_str(&format!(
            "| {} | {} | {} | {} | {:.1} | {:.1} | {:.3} | {:.3} | {:.0}% | {:.3} | {regions} | {:.2}% |\n",
            r.scene,
            r.variant,
            r.resolution,
            r.bounces,
            r.frame_ms,
            r.memory_mib,
            r.flip,
            r.flip_direct_only,
            100.0 * r.flip / r.flip_direct_only.max(1e-9),
            r.mean_ratio,
            100.0 * r.reference_noise
        ));
    }
    s.push_str(
        "\nFLIP by distance from the camera, over thirds of the pixels that see a surface:\n\n| scene | variant | N | near | middle | far | thirds parted at |\n|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let [near, middle, far] = r.flip_by_distance;
        let [a, b] = r.distance_edges;
        s.push_str(&format!(
            "| {} | {} | {} | {near:.4} | {middle:.4} | {far:.4} | {a:.2} / {b:.2} m |\n",
            r.scene, r.variant, r.resolution
        ));
    }
    let spread =
        |v: [f32; 3], digits: usize| format!("{:.*} / {:.*} / {:.*}", digits, v[0], digits, v[1], digits, v[2]);
    if rows.iter().any(|r| r.lattices.is_some()) {
        s.push_str(
            "\nOn other placements of the lattice (moved by under a voxel, a clipmap's of its coarsest level; least / mean / most, the row's own among them):\n\n| scene | variant | N | placements | FLIP | mean / reference | judged regions' ratios |\n|---|---|---|---|---|---|---|\n",
        );
        for r in rows {
            let Some(l) = &r.lattices else { continue };
            let judged = || l.region_ratio.iter().zip(&r.regions).filter(|(_, g)| g.judged).map(|(v, _)| v);
            let lo = judged().map(|v| v[0]).fold(f32::INFINITY, f32::min);
            let hi = judged().map(|v| v[2]).fold(f32::NEG_INFINITY, f32::max);
            s.push_str(&format!(
                "| {} | {} | {} | {} | {} | {} | {lo:.2}–{hi:.2} |\n",
                r.scene,
                r.variant,
                r.resolution,
                l.placements,
                spread(l.flip, 4),
                spread(l.mean_ratio, 3)
            ));
        }
    }
    for r in rows {
        let (head, rule) = if r.lattices.is_some() { (" over lattices |", "---|") } else { ("", "") };
        s.push_str(&format!(
            "\nIndirect light per region, {} {} {}³ (full minus direct, linear):\n\n| region | pixels | reference | vct | ratio |{head}\n|---|---|---|---|---|{rule}\n",
            r.scene, r.variant, r.resolution
        ));
        for (i, g) in r.regions.iter().enumerate() {
            let f = |c: [f32; 3]| format!("{:.4} {:.4} {:.4}", c[0], c[1], c[2]);
            let over = r.lattices.as_ref().map_or(String::new(), |l| format!(" {} |", spread(l.region_ratio[i], 2)));
            let judged = if g.judged { "" } else { " (not judged: nearly dark in the reference)" };
            s.push_str(&format!(
                "| {} | {} | {} | {} | {:.2}{judged} |{over}\n",
                g.region,
                g.pixels,
                f(g.reference),
                f(g.vct),
                g.ratio
            ));
        }
    }
    s
}

/// Writes accuracy.json, accuracy.csv, summary.md, the FLIP maps and indirect-light comparisons
/// (of every row, or with `maps_of_defaults` of the thesis' and the default model only) and the
/// speed-against-accuracy chart into `dir`.
pub fn write(dir: &Path, rows: &[AccuracyRow], maps_of_defaults: bool) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).map_err(|source| Error::Io { path: dir.to_path_buf(), source })?;
    let put = |name: &str, text: &str| -> Result<PathBuf> {
        let p = dir.join(name);
        std::fs::write(&p, text).map_err(|source| Error::Io { path: p.clone(), source })?;
        Ok(p)
    };
    let mut files = Vec::new();
    let json =
        serde_json::to_string_pretty(rows).map_err(|e| Error::input(dir.join("accuracy.json"), e.to_string()))?;
    files.push(put("accuracy.json", &json)?);
    let mut csv = String::from(
        "scene,variant,resolution,bounces,frame_ms,memory_mib,flip,flip_direct_only,mean_ratio,worst_region_ratio,region_log_error,lattices,flip_lattice_min,flip_lattice_mean,flip_lattice_max,flip_near,flip_middle,flip_far\n",
    );
    for r in rows {
        let worst = r.regions.iter().filter(|g| g.judged).map(|g| g.ratio).fold(1.0f32, |w, x| {
            if (x - 1.0).abs() > (w - 1.0).abs() {
                x
            } else {
                w
            }
        });
        let lattices = r.lattices.as_ref().map_or(",,,".to_string(), |l| {
            format!("{},{:.5},{:.5},{:.5}", l.placements, l.flip[0], l.flip[1], l.flip[2])
        });
        csv.push_str(&format!(
            "{},\"{}\",{},{},{:.3},{:.2},{:.5},{:.5},{:.4},{:.4},{},{lattices},{:.5},{:.5},{:.5}\n",
            r.scene,
            r.variant,
            r.resolution,
            r.bounces,
            r.frame_ms,
            r.memory_mib,
            r.flip,
            r.flip_direct_only,
            r.mean_ratio,
            worst,
            region_log_error(&r.regions).map_or(String::new(), |e| format!("{e:.4}")),
            r.flip_by_distance[0],
            r.flip_by_distance[1],
            r.flip_by_distance[2]
        ));
    }
    files.push(put("accuracy.csv", &csv)?);
    files.push(put("summary.md", &summary(rows))?);
    // Rows read back from accuracy.json carry no images.
    let imaged = rows.iter().filter(|r| !r.flip_map.is_empty());
    for r in imaged.filter(|r| !maps_of_defaults || r.variant == "default" || r.variant == "thesis") {
        let slug: String = format!("flip-{}-{}-{}", r.scene, r.variant, r.resolution)
            .chars()
            .map(|c| if c.is_ascii_alphanumeric() || c == '-' { c } else { '_' })
            .collect();
        let p = dir.join(format!("{slug}.png"));
        image::save_buffer(&p, &r.flip_map, r.width, r.height, image::ColorType::Rgb8)
            .map_err(|source| Error::Image { path: p.clone(), source })?;
        files.push(p);
        let p = dir.join(format!("{}.png", slug.replacen("flip-", "indirect-", 1)));
        image::save_buffer(&p, &r.indirect_pair, 2 * r.width, r.height, image::ColorType::Rgb8)
            .map_err(|source| Error::Image { path: p.clone(), source })?;
        files.push(p);
    }
    files.extend(charts::draw_accuracy(dir, rows, charts::Cost::Time)?);
    // Grids that spread the same voxels differently (--layouts): FLIP over memory too.
    if rows.iter().any(|r| r.variant.starts_with("warp") || r.variant.starts_with("clipmap")) {
        files.extend(charts::draw_accuracy(dir, rows, charts::Cost::Memory)?);
    }
    Ok(files)
}
