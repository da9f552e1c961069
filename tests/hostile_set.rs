//! The voxelizers against the exact triangle/box coverage on the hostile-geometry set
//! (assets/hostile/). Conservative rasterization without the extension must write every voxel each
//! triangle touches and nothing else; sampling (MSAA) must not.

mod common;

use vct::bench::hostile::{self, HostileRow};
use vct::voxel::{Coverage, VoxelizeMethod};

fn rows(methods: &[VoxelizeMethod]) -> Vec<HostileRow> {
    let ctx = common::context();
    let rows = hostile::run(&ctx, methods, 64, &|_| {}).unwrap();
    common::assert_clean(&ctx);
    println!("{}", hostile::table(&rows));
    rows
}

#[test]
fn conservative_rasterization_is_exact_on_hostile_meshes_and_msaa_is_not() {
    let rows = rows(&[VoxelizeMethod::raster(Coverage::Conservative), VoxelizeMethod::raster(Coverage::Msaa)]);
    let get = |mesh: &str, method: &str| rows.iter().find(|r| r.mesh == mesh && r.method == method).unwrap();
    for mesh in hostile::MESHES {
        let c = get(mesh, "raster-conservative");
        assert!(c.recall >= 0.995 && c.precision >= 0.999, "{mesh}: conservative {c:?}");
    }
    // Sampling drops what covers no sample: sub-voxel triangles, slivers and needles.
    for mesh in ["subvoxel", "slivers", "needles"] {
        let m = get(mesh, "raster-msaa");
        assert!(m.recall < 0.9, "{mesh}: MSAA should lose thin triangles, recall {}", m.recall);
    }
}

#[test]
fn conservative_coverage_needs_the_exact_depth_span() {
    let ctx = common::context();
    let scene = vct::scene::Scene::load(&hostile::mesh_path("fans")).unwrap();
    let m = VoxelizeMethod::Raster { coverage: Coverage::Conservative, viewport_scale: 1.0, depth_span: false };
    let err = vct::voxel::headless::voxelize(&ctx, &scene, m, 32, 1).err().expect("accepted without the depth span");
    assert!(err.to_string().contains("no-depth-span"), "{err}");
}

#[test]
fn tessellation_with_the_neighbour_fill_is_exact_on_hostile_meshes_and_without_it_is_not() {
    let no_fill = VoxelizeMethod::Tess { neighbours: false, level_scale: 3.0, subdivide: true, min_level: true };
    let rows = rows(&[VoxelizeMethod::tess(), no_fill]);
    for mesh in hostile::MESHES {
        let r: Vec<&HostileRow> = rows.iter().filter(|r| r.mesh == mesh).collect();
        let (fill, sampled) = (r[0], r[1]);
        assert!(fill.recall >= 0.99 && fill.precision >= 0.999, "{mesh}: tessellation with the fill {fill:?}");
        if mesh != "fans" {
            assert!(
                sampled.recall < fill.recall - 0.01,
                "{mesh}: sampling alone {} vs {}",
                sampled.recall,
                fill.recall
            );
        }
    }
}
