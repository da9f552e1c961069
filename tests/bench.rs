//! `vct bench --report DIR --quick` (the CI variant of the report's suite) writes the sweep's
//! CSV, JSON and charts, with the expected columns and one row per configuration, the point
//! voxelizer's density sweep among them, and the report's pages: every section present and its
//! tables filled, every chart inline, nothing from the network. `vct bench --accuracy` measures
//! layouts and lattice placements.

use vct::bench::accuracy::{distance_bands, region_log_error, RegionRow};

/// Runs `vct bench ARGS --validation --out DIR/run` in a fresh temporary DIR; returns DIR/run
/// once it succeeded.
fn bench(name: &str, args: &[&str]) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("vct-{name}-{}", std::process::id()));
    let out = dir.join("run");
    vct_bench(&[args, &["--out", out.to_str().unwrap()]].concat());
    out
}

/// Runs `vct bench ARGS --validation` (ARGS holding the output folder) and returns its output
/// once it succeeded.
fn vct_bench(args: &[&str]) -> String {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_vct"))
        .arg("bench")
        .args(args)
        .arg("--validation")
        .env("XDG_RUNTIME_DIR", std::env::var("XDG_RUNTIME_DIR").unwrap_or("/tmp".into()))
        .output()
        .unwrap();
    let text = format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    assert!(o.status.success(), "{text}");
    text
}

#[test]
fn quick_report_writes_the_suites_data_and_both_pages() {
    let dir = std::env::temp_dir().join(format!("vct-report-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    vct_bench(&["--report", dir.to_str().unwrap(), "--quick"]);
    report_pages_are_whole(&dir);
    report_rewrites_from_its_data_and_takes_a_gpu_run(&dir);
    quick_sweep_writes_csv_json_and_charts(&dir.join("data/sweep"));
}

/// The report's README.md and index.html: the stamp, every section with a filled table, every
/// chart inline as SVG, and nothing a browser would fetch.
fn report_pages_are_whole(dir: &std::path::Path) {
    let md = std::fs::read_to_string(dir.join("README.md")).unwrap();
    for stamp in ["| commit |", "| device |", "| driver |", "| host |", "| command |"] {
        assert!(md.contains(stamp), "README.md has no {stamp} line");
    }
    // Each section: its heading, then a table with a header, a rule and at least one row, no
    // cell empty.
    let sections: Vec<&str> = md.split("\n## ").skip(1).collect();
    assert_eq!(sections.len(), vct::bench::report::page::SECTIONS.len(), "{md}");
    for s in &sections {
        let rows: Vec<&str> = s.lines().filter(|l| l.starts_with('|')).collect();
        assert!(rows.len() >= 3, "a section without a filled table:\n{s}");
        for r in rows {
            assert!(!r.contains("|  |") && !r.contains("| |") || r.starts_with("|  |  |"), "an empty cell: {r}");
        }
    }
    let html = std::fs::read_to_string(dir.join("index.html")).unwrap();
    for id in vct::bench::report::page::SECTIONS {
        let start = html.find(&format!("<section id=\"{id}\">")).unwrap_or_else(|| panic!("no section {id}"));
        let end = start + html[start..].find("</section>").unwrap();
        let body = &html[start..end];
        assert!(body.contains("<table>") && body.contains("<td>"), "section {id} has no filled table");
    }
    for chart in [
        "speed_vs_accuracy",
        "voxelize_time",
        "passes_stacked",
        "tess_over_raster",
        "cost_vs_triangles",
        "storage_memory_vs_flip",
        "storage_time_vs_flip",
        "points_density",
        "gi_scale",
        "accuracy",
        "stability_tess_limit",
        "stability_raster_cracks",
        "stability_subvoxel",
        "stability_light_leaking",
        "stability_temporal_flicker",
        "stability_self_illumination",
    ] {
        let start = html.find(&format!("id=\"chart-{chart}\"")).unwrap_or_else(|| panic!("no chart {chart}"));
        let end = start + html[start..].find("</figure>").unwrap();
        let figure = &html[start..end];
        assert!(figure.contains("<svg") && figure.contains("</svg>") && figure.len() > 2000, "chart {chart} is empty");
    }
    // Offline: no script, no stylesheet or image fetched, no link off the page (the SVG
    // namespace is a name, not a fetch).
    let fetches = html.replace("xmlns=\"http://www.w3.org/2000/svg\"", "");
    for bad in ["<script", "<link", "src=\"http", "href=\"http", "url(http", "@import"] {
        assert!(!fetches.contains(bad), "index.html contains {bad}");
    }
}

/// `--rewrite` writes the same pages from the data alone; `--gpu RUN` adds a GPU run's data as
/// a section of its own, and a folder with no run in it is an error naming it.
fn report_rewrites_from_its_data_and_takes_a_gpu_run(dir: &std::path::Path) {
    let before = std::fs::read_to_string(dir.join("README.md")).unwrap();
    vct_bench(&["--report", dir.to_str().unwrap(), "--rewrite"]);
    assert_eq!(std::fs::read_to_string(dir.join("README.md")).unwrap(), before);
    let run = dir.with_extension("gpu-run");
    std::fs::create_dir_all(run.join("bench/main")).unwrap();
    std::fs::copy(dir.join("data/sweep/results.json"), run.join("bench/main/results.json")).unwrap();
    let copy = dir.with_extension("copy");
    let _ = std::fs::remove_dir_all(&copy);
    std::fs::create_dir_all(&copy).unwrap();
    std::fs::create_dir_all(copy.join("data/sweep")).unwrap();
    for f in ["stamp.json", "sweep/results.json"] {
        std::fs::copy(dir.join("data").join(f), copy.join("data").join(f)).unwrap();
    }
    vct_bench(&["--report", copy.to_str().unwrap(), "--rewrite", "--gpu", run.to_str().unwrap()]);
    let md = std::fs::read_to_string(copy.join("README.md")).unwrap();
    assert!(md.contains("## On a GPU") && md.contains("### How fast is each voxelizer"), "{md}");
    let html = std::fs::read_to_string(copy.join("index.html")).unwrap();
    assert!(html.contains("<section id=\"gpu-voxelizers\">") && html.contains("id=\"chart-gpu-speed_vs_accuracy\""));
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_vct"))
        .args(["bench", "--report", copy.to_str().unwrap(), "--rewrite", "--gpu", "/nonexistent-gpu-run"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("/nonexistent-gpu-run"), "{err}");
}

fn quick_sweep_writes_csv_json_and_charts(out: &std::path::Path) {
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next().unwrap(), vct::bench::CSV_HEADER);
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    // Cornell × {32, 64} × {tess, raster-msaa, raster-none, raster-conservative, points (,
    // raster-hw where offered)} with the default storage, and the default voxelizer (raster-conservative
    // on lavapipe, which has no hardware conservative rasterization) with the others
    // offered: dense (and the pool beside residency where that is the default).
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap()).unwrap();
    let stored = json["default_storage"].as_str().unwrap();
    let others = if stored == "resident" { 4 } else { 2 };
    assert!(rows.len() == 10 + others || rows.len() == 12 + others, "{} rows:\n{csv}", rows.len());
    let cols = vct::bench::CSV_HEADER.split(',').count();
    for r in &rows {
        assert_eq!(r.len(), cols);
        let num = |name: &str| -> f64 {
            let i = vct::bench::CSV_HEADER.split(',').position(|c| c == name).unwrap();
            r[i].parse().unwrap()
        };
        assert!(num("total_ms") > 0.0 && num("voxelize_ms") > 0.0, "{r:?}");
        assert!((0.9..=1.0).contains(&num("iou")) && (0.0..1.0).contains(&num("flip")), "{r:?}");
    }
    for (label, n) in [("tess", 32), ("raster-msaa", 64), ("raster-none", 64), ("points", 32), ("points", 64)] {
        assert!(rows.iter().any(|r| r[2] == label && r[3] == n.to_string()), "no {label} {n} row");
    }
    // Dense storage beside the default (the pool; residency on a device that offers it, which
    // binds every block of these small grids): the same image against the reference, and with
    // the pool, more memory.
    let col = |name: &str| vct::bench::CSV_HEADER.split(',').position(|c| c == name).unwrap();
    for n in ["32", "64"] {
        let find = |storage: &str| {
            rows.iter()
                .find(|r| r[2] == "raster-conservative" && r[3] == n && r[col("storage")] == storage)
                .unwrap_or_else(|| panic!("no {storage} row at {n}"))
        };
        let (s, d) = (find(stored), find("dense"));
        let f = |r: &Vec<&str>, c: &str| -> f64 { r[col(c)].parse().unwrap() };
        assert!(stored != "sparse" || f(s, "memory_mib") < f(d, "memory_mib"), "{s:?} {d:?}");
        assert!((f(s, "flip") - f(d, "flip")).abs() <= 0.005, "{s:?} {d:?}");
    }
    assert_eq!(json["rows"].as_array().unwrap().len(), rows.len());
    // Three voxelizers (tess, raster-msaa, points) over three triangle counts.
    assert!(json["triangle_sweep"].as_array().unwrap().len() >= 9);
    // The point voxelizer's density sweep at 32³: without refinement, recall grows with the
    // density; precision stays exact (a point lies on its triangle).
    let sweep = json["density_sweep"].as_array().unwrap();
    assert_eq!(sweep.len(), 2 * vct::bench::points::QUICK_DENSITIES.len());
    let recall = |refine: bool, density: f64| {
        let d = sweep.iter().find(|d| d["refine"] == refine && d["density"].as_f64() == Some(density)).unwrap();
        assert_eq!(d["row"]["precision"].as_f64(), Some(1.0), "{d}");
        d["row"]["recall"].as_f64().unwrap()
    };
    let [low, high] = vct::bench::points::QUICK_DENSITIES.map(|d| d as f64);
    assert!(recall(false, high) > recall(false, low), "{sweep:?}");
    assert!(recall(true, low) >= recall(false, low), "{sweep:?}");
    // The diffuse cones at one pixel in 4 and 16, beside every pixel: FLIP against the
    // reference moves little, and accumulated over a still camera's frames it is every pixel's.
    let scaled = json["gi_scale_sweep"].as_array().unwrap();
    assert_eq!(scaled.len(), 2 * vct::bench::gi_scale::SCALES.len());
    let full = rows
        .iter()
        .find(|r| r[2] == "raster-conservative" && r[3] == "32" && r[col("storage")] == stored)
        .map(|r| r[col("flip")].parse::<f64>().unwrap())
        .unwrap();
    for x in scaled {
        let flip = x["row"]["flip"].as_f64().unwrap();
        assert!((flip - full).abs() < 0.02, "GI scale {}: FLIP {flip} against {full}", x["scale"]);
        if x["accumulate"].as_bool().unwrap() {
            assert!((flip - full).abs() < 0.005, "GI scale {} accumulated: FLIP {flip} against {full}", x["scale"]);
        }
    }
    assert!(!json["device"].as_str().unwrap().is_empty());
    for chart in [
        "voxelize_time",
        "passes_stacked",
        "speed_vs_accuracy",
        "cost_vs_triangles",
        "storage_memory_vs_flip",
        "storage_time_vs_flip",
        "points_density",
        "flip_against_recall_cornell",
        "gi_scale",
    ] {
        // The report keeps each chart as SVG only.
        let p = out.join(format!("{chart}.svg"));
        assert!(std::fs::metadata(&p).map(|m| m.len() > 1000).unwrap_or(false), "{} missing or empty", p.display());
    }
    replot_draws_what_a_results_file_holds_and_refuses_an_empty_one(out, &json);
}

/// `vct bench --replot DIR` reads a results file a user may hand it: one configuration draws
/// what it can, and one without any is an error naming the file, within seconds (on an empty
/// series plotters searches for axis ticks forever).
fn replot_draws_what_a_results_file_holds_and_refuses_an_empty_one(out: &std::path::Path, json: &serde_json::Value) {
    let replot = |name: &str, keep: usize| {
        let dir = out.parent().unwrap().join(name);
        std::fs::create_dir_all(&dir).unwrap();
        let mut j = json.clone();
        for key in ["rows", "density_sweep", "gi_scale_sweep"] {
            j[key].as_array_mut().unwrap().truncate(keep);
        }
        std::fs::write(dir.join("results.json"), serde_json::to_string(&j).unwrap()).unwrap();
        let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_vct"))
            .args(["bench", "--replot", dir.to_str().unwrap()])
            .stderr(std::process::Stdio::piped())
            .stdout(std::process::Stdio::null())
            .spawn()
            .unwrap();
        let started = std::time::Instant::now();
        while child.try_wait().unwrap().is_none() {
            if started.elapsed().as_secs() > 60 {
                child.kill().unwrap();
                panic!("replot of {name} still running after 60 s");
            }
            std::thread::sleep(std::time::Duration::from_millis(50));
        }
        let o = child.wait_with_output().unwrap();
        (o.status.code(), String::from_utf8_lossy(&o.stderr).into_owned(), dir)
    };
    let (code, err, dir) = replot("one-row", 1);
    assert_eq!(code, Some(0), "{err}");
    assert!(dir.join("speed_vs_accuracy.png").exists());
    let (code, err, _) = replot("no-rows", 0);
    assert_eq!(code, Some(1), "{err}");
    assert!(err.contains("no-rows/results.json") && err.contains("no configuration"), "{err}");
}

/// `vct bench --accuracy --layouts` measures each scene on its fitted grid and on warped grids of
/// the same voxels (Freed 2018 §4.6.1) against the path tracer, with the volume's memory, and
/// charts FLIP against memory.
#[test]
fn accuracy_bench_compares_layouts_at_the_same_voxels() {
    let out = bench("layouts", &["--accuracy", "--quick", "--layouts", "--warp-slopes", "0.5,0.25"]);
    let csv = std::fs::read_to_string(out.join("accuracy/accuracy.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|c| *c == name).unwrap();
    let rows: Vec<Vec<&str>> = csv.lines().skip(1).map(|l| l.split(',').collect()).collect();
    // Per embedded scene: its fitted grid, then the two function warps and the perspective warp.
    let variants: Vec<&str> = rows.iter().map(|r| r[col("variant")]).collect();
    assert!(!variants.is_empty() && variants.len().is_multiple_of(4), "{csv}");
    for v in variants.chunks(4) {
        let want = ["\"default\"", "\"warp function 0.5\"", "\"warp function 0.25\"", "\"warp perspective 0.25\""];
        assert_eq!(v, want, "{csv}");
    }
    for r in &rows {
        let num = |name: &str| -> f64 { r[col(name)].parse().unwrap() };
        assert!(num("memory_mib") > 0.0 && num("frame_ms") > 0.0, "{r:?}");
        assert!((0.0..1.0).contains(&num("flip")) && num("flip") > 0.0, "{r:?}");
        // Every region of the embedded Cornell boxes is judged, none matched exactly.
        assert!(num("region_log_error") > 0.0 && num("region_log_error").is_finite(), "{r:?}");
        // FLIP over the thirds by distance: each a mean of per-pixel errors, not all alike.
        let thirds = [num("flip_near"), num("flip_middle"), num("flip_far")];
        assert!(thirds.iter().all(|f| (0.0..1.0).contains(f) && *f > 0.0), "{r:?}");
        assert!(thirds[0] != thirds[1] || thirds[1] != thirds[2], "{r:?}");
    }
    // The warp changes the image: its FLIP is not the fitted grid's.
    for r in rows.chunks(4) {
        assert_ne!(r[0][col("flip")], r[2][col("flip")], "{csv}");
        assert_ne!(r[0][col("flip")], r[3][col("flip")], "{csv}");
    }
    assert!(out.join("accuracy/accuracy-memory.png").exists() && out.join("accuracy/accuracy.png").exists());
    let _ = std::fs::remove_dir_all(out.parent().unwrap());
}

/// `vct bench --accuracy --lattices K` measures each fitted grid again on K − 1 placements of
/// its lattice moved by under a voxel, and reports the spread of its figures with the row's own
/// among them: a shift the renderer ignored would give every placement the same image.
#[test]
fn accuracy_bench_measures_the_spread_over_lattice_placements() {
    let out = bench("lattices", &["--accuracy", "--quick", "--lattices", "3"]);
    let csv = std::fs::read_to_string(out.join("accuracy/accuracy.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|c| *c == name).unwrap_or_else(|| panic!("no {name}: {csv}"));
    let rows: Vec<Vec<&str>> = csv.lines().skip(1).map(|l| l.split(',').collect()).collect();
    assert!(!rows.is_empty(), "{csv}");
    for r in &rows {
        let num = |name: &str| -> f64 { r[col(name)].parse().unwrap_or_else(|_| panic!("{name} in {r:?}")) };
        assert_eq!(num("lattices"), 3.0, "{r:?}");
        let (lo, mean, hi, own) =
            (num("flip_lattice_min"), num("flip_lattice_mean"), num("flip_lattice_max"), num("flip"));
        assert!(lo <= own && own <= hi && lo <= mean && mean <= hi, "{r:?}");
        assert!(hi > lo, "every lattice placement gave the same image: {r:?}");
    }
    let summary = std::fs::read_to_string(out.join("accuracy/summary.md")).unwrap();
    assert!(summary.contains("On other placements of the lattice") && summary.contains("over lattices"), "{summary}");
    let _ = std::fs::remove_dir_all(out.parent().unwrap());
}

fn region(pixels: usize, ratio: f32, judged: bool) -> RegionRow {
    RegionRow { region: String::new(), pixels, reference: [1.0; 3], vct: [ratio; 3], ratio, judged }
}

/// The regions' figure in the accuracy bench's summary and CSV (`region_log_error`): the mean
/// |ln ratio| over the judged regions' pixels.
#[test]
fn region_log_error_counts_too_dark_and_too_bright_alike_by_pixels() {
    assert_eq!(region_log_error(&[region(10, 1.0, true), region(5, 1.0, true)]), Some(0.0));
    // Half and twice the reference's light, in regions of 3 and 1 pixels: ln 2 either way.
    let e = region_log_error(&[region(3, 0.5, true), region(1, 2.0, true)]).unwrap();
    assert!((e - std::f32::consts::LN_2).abs() < 1e-6, "{e}");
    // Pixel-weighted: a large exact region dilutes a small wrong one.
    let e = region_log_error(&[region(3, 1.0, true), region(1, 2.0, true)]).unwrap();
    assert!((e - std::f32::consts::LN_2 / 4.0).abs() < 1e-6, "{e}");
    // Regions that are not judged (nearly dark in the reference) do not count.
    assert_eq!(region_log_error(&[region(3, 1.0, true), region(100, 1e6, false)]), Some(0.0));
    assert_eq!(region_log_error(&[region(100, 1e6, false)]), None);
}

/// The accuracy bench's thirds by distance (`distance_bands`): equal in pixels, nearest first,
/// pixels that see no surface in none.
#[test]
fn distance_bands_split_the_surface_pixels_into_equal_thirds() {
    let mut d: Vec<Option<f32>> = [5.0, 1.0, 9.0, 2.0, 7.0, 3.0, 8.0, 4.0, 6.0, 10.0, 11.0, 12.0].map(Some).to_vec();
    d.insert(2, None);
    d.insert(7, None);
    let (band, edges) = distance_bands(&d);
    let count = |k: u8| band.iter().filter(|b| **b == Some(k)).count();
    assert_eq!((count(0), count(1), count(2)), (4, 4, 4), "{band:?}");
    assert_eq!(edges, [5.0, 9.0]);
    for (d, b) in d.iter().zip(&band) {
        match (d, b) {
            (None, None) => {}
            (Some(d), Some(b)) => assert_eq!(*b, (*d >= 5.0) as u8 + (*d >= 9.0) as u8, "{d}"),
            _ => panic!("{d:?} in {b:?}"),
        }
    }
}
