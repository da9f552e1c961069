//! Global illumination: the radiance mip chain against a CPU box filter, the cone
//! tracer against a CPU model, and the Cornell box's global illumination (colour bleeding,
//! a lit ceiling, ambient occlusion, no light from nowhere, the tessellation and raster
//! voxelizers agreeing).

mod common;

use ash::vk;
use glam::{Vec3, Vec4};
use gpu_allocator::MemoryLocation;
use half::f16;
use vct::gpu::{self, shaders, Binding, Buffer, DescriptorSet, Image, ImageDesc, Pipeline, Sampler, Stage};
use vct::reference::cone::{ConeParams, MipVolume};
use vct::render::{FrameImages, RenderOptions, Renderer, View};
use vct::scene::Scene;
use vct::voxel::{Coverage, VoxelizeMethod};

fn f16s(bytes: &[u8]) -> Vec<f32> {
    bytes.chunks_exact(2).map(|b| f16::from_le_bytes([b[0], b[1]]).to_f32()).collect()
}

fn render(scene: Scene, options: RenderOptions) -> FrameImages {
    let ctx = common::context();
    let r = Renderer::new(&ctx, scene, options).unwrap();
    r.render().unwrap();
    let f = r.read_frame().unwrap();
    drop(r);
    common::assert_clean(&ctx);
    f
}

fn options(view: View, res: u32) -> RenderOptions {
    RenderOptions { method: VoxelizeMethod::raster(Coverage::Msaa), resolution: Some(res), view, ..Default::default() }
}

#[test]
fn every_mip_level_is_the_box_filter_of_the_level_below() {
    let ctx = common::context();
    // The isotropic chain (the directional model builds only its level 0 and its own chains).
    let mut scene = Scene::embedded_default().unwrap();
    scene.settings.gi.filter = vct::scene::file::Filter::Iso;
    let r = Renderer::new(&ctx, scene, options(View::Full, 32)).unwrap();
    r.render().unwrap();
    // Level 0 is stored as the voxels are (a brick pool by default), the chain above it dense.
    let chain = &r.radiance.chain;
    let levels: Vec<Vec<f32>> = std::iter::once(f16s(&r.voxels.read_dense(r.radiance.level0()).unwrap()))
        .chain(
            (1..r.radiance.levels)
                .map(|l| f16s(&gpu::read_image(&ctx, chain, vk::ImageLayout::GENERAL, l - 1).unwrap())),
        )
        .collect();
    assert!(levels[0].iter().any(|&v| v > 0.0), "level 0 is empty: nothing was injected");
    for l in 1..levels.len() {
        let n = (32u32 >> l) as usize;
        let m = 2 * n;
        for z in 0..n {
            for y in 0..n {
                for x in 0..n {
                    for c in 0..4 {
                        let mut sum = 0.0;
                        for i in 0..8 {
                            let (dx, dy, dz) = (i & 1, (i >> 1) & 1, i >> 2);
                            sum += levels[l - 1][4 * ((2 * x + dx) + m * ((2 * y + dy) + m * (2 * z + dz))) + c];
                        }
                        let want = sum / 8.0;
                        let got = levels[l][4 * (x + n * (y + n * z)) + c];
                        assert!(
                            (got - want).abs() <= want.abs() * 2e-3 + 1e-5,
                            "level {l} ({x},{y},{z}) channel {c}: {got} vs {want}"
                        );
                    }
                }
            }
        }
    }
    drop(r);
    common::assert_clean(&ctx);
}

#[test]
fn anisotropic_level_one_composites_front_to_back_along_each_axis() {
    let ctx = common::context();
    let mut scene = Scene::embedded_default().unwrap();
    scene.settings.gi.filter = vct::scene::file::Filter::Aniso;
    let r = Renderer::new(&ctx, scene, options(View::Full, 16)).unwrap();
    r.render().unwrap();
    let base = f16s(&r.voxels.read_dense(r.radiance.level0()).unwrap());
    // Stored as the voxels are (a brick pool by default): read back as the grid.
    let sides: Vec<u32> = bytemuck::pod_collect_to_vec(&r.voxels.read_dense(&r.radiance.lit_side).unwrap());
    let lit_sides = sides.iter().filter(|&&s| s >> 24 != 0).count();
    assert!(lit_sides > 100, "injection should record the lit side of the lit voxels ({lit_sides})");
    // A child seen by a cone travelling along `dir` shows its light only where the lit side faces
    // the cone (soft edge over dot(n, dir) in [0, 1/4]).
    let side =
        |s: u32| Vec3::new((s & 0xff) as f32, ((s >> 8) & 0xff) as f32, ((s >> 16) & 0xff) as f32) / 255.0 * 2.0 - 1.0;
    let texel = |x: usize, y: usize, z: usize, dir: Vec3| {
        let i = x + 16 * (y + 16 * z);
        let t = Vec4::from_slice(&base[4 * i..][..4]);
        let s = sides[i];
        if s >> 24 == 0 {
            return t;
        }
        (t.truncate() * (1.0 - 4.0 * side(s).dot(dir)).clamp(0.0, 1.0)).extend(t.w)
    };
    // A dark, unlit child behind a lit neighbour's face across the chain's axis is the far voxel
    // of a surface on a voxel face, which edge-on adds no thickness: empty in that chain.
    let behind_lit_face = |c: [usize; 3], axis: usize| {
        let i = c[0] + 16 * (c[1] + 16 * c[2]);
        let t = Vec4::from_slice(&base[4 * i..][..4]);
        if sides[i] >> 24 != 0 || t.w <= 0.0 || t.truncate() != Vec3::ZERO {
            return false;
        }
        [(axis + 1) % 3, (axis + 2) % 3].into_iter().any(|b| {
            [-1i32, 1].into_iter().any(|s| {
                let mut nb = c.map(|v| v as i32);
                nb[b] += s;
                if nb.iter().any(|&v| !(0..16).contains(&v)) {
                    return false;
                }
                let n = sides[(nb[0] + 16 * (nb[1] + 16 * nb[2])) as usize];
                let l = side(n);
                let most = l.abs().max_element();
                n >> 24 != 0 && n & 0xff_ffff != 0 && l[b] * s as f32 > 0.0 && l[b].abs() >= most
            })
        })
    };
    let mut hidden = 0;
    let mut behind = 0;
    // The six chains share one atlas, stacked along one axis with empty separators between them.
    let atlas = f16s(&gpu::read_image(&ctx, &r.radiance.aniso, vk::ImageLayout::GENERAL, 0).unwrap());
    let layout = r.radiance.atlas;
    let e = layout.extent();
    let (width, height) = (e.width as usize, e.height as usize);
    for d in 0..6 {
        let got: Vec<f32> = (0..8)
            .flat_map(|z| (0..8).flat_map(move |y| (0..8).map(move |x| [x, y, z])))
            .flat_map(|mut c| {
                c[layout.axis] += d * layout.pitch as usize;
                let start = 4 * (c[0] + width * (c[1] + height * c[2]));
                atlas[start..start + 4].to_vec()
            })
            .collect();
        let axis = d / 2;
        let positive = d % 2 == 0;
        let mut dir = Vec3::ZERO;
        dir[axis] = if positive { 1.0 } else { -1.0 };
        let mut nonzero = 0;
        for z in 0..8 {
            for y in 0..8 {
                for x in 0..8 {
                    let mut sum = Vec4::ZERO;
                    for i in 0..4 {
                        let mut c = [2 * x, 2 * y, 2 * z];
                        c[(axis + 1) % 3] += i & 1;
                        c[(axis + 2) % 3] += i >> 1;
                        let mut c2 = c;
                        c2[axis] += 1;
                        let (near, far) = if positive { (c, c2) } else { (c2, c) };
                        let seen = |c: [usize; 3]| {
                            if behind_lit_face(c, axis) {
                                Vec4::ZERO
                            } else {
                                texel(c[0], c[1], c[2], dir)
                            }
                        };
                        behind += behind_lit_face(near, axis) as usize + behind_lit_face(far, axis) as usize;
                        let (n, f) = (seen(near), seen(far));
                        let unweighted = texel(near[0], near[1], near[2], Vec3::ZERO);
                        hidden += (unweighted.truncate() != n.truncate()) as usize;
                        sum += n + (1.0 - n.w) * f;
                    }
                    let want = sum / 4.0;
                    let g = Vec4::from_slice(&got[4 * (x + 8 * (y + 8 * z))..][..4]);
                    assert!(
                        (g - want).abs().max_element() <= want.abs().max_element() * 2e-3 + 1e-4,
                        "direction {d} ({x},{y},{z}): {g} vs {want}"
                    );
                    nonzero += (want.w > 0.0) as usize;
                }
            }
        }
        assert!(nonzero > 20, "direction {d}: the volume is nearly empty");
    }
    // The separators between the chains stay empty: trilinear filtering meets zeros at a
    // chain's edge. They are at least one texel at the coarsest mip.
    let chain = layout.chain[layout.axis] as usize;
    let separator = layout.pitch as usize - chain;
    assert!(separator >= 1 << (r.radiance.aniso.desc.mip_levels - 1), "separators of {separator} texels");
    let dirty = (0..e.depth as usize)
        .flat_map(|z| (0..height).flat_map(move |y| (0..width).map(move |x| [x, y, z])))
        .filter(|c| c[layout.axis] % layout.pitch as usize >= chain)
        .any(|c| atlas[4 * (c[0] + width * (c[1] + height * c[2]))..][..4].iter().any(|&v| v != 0.0));
    assert!(!dirty, "a separator of the directional atlas was written");
    assert!(hidden > 100, "lit faces seen from behind should be dark ({hidden} children hidden)");
    // The room's walls lie on voxel faces at 16³ (the fitted grid's padding is a whole voxel).
    assert!(behind > 20, "the far voxels of the lit walls should be empty edge-on ({behind} children)");
    drop(r);
    common::assert_clean(&ctx);
}

/// A 16³ volume: an emissive slab, a grey blob and empty space, with its box-filtered mips, all
/// rounded to f16 as the GPU stores them.
fn synthetic_volume() -> MipVolume {
    let n = 16u32;
    let round = |v: Vec4| Vec4::from_array(v.to_array().map(|c| f16::from_f32(c).to_f32()));
    let mut base = Vec::new();
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                let slab = (11..13).contains(&x);
                let blob = Vec3::new(x as f32, y as f32, z as f32).distance(Vec3::new(5.0, 10.0, 6.0)) < 3.0;
                base.push(round(if slab {
                    Vec4::new(2.0, 1.0, 0.5, 1.0)
                } else if blob {
                    Vec4::new(0.3, 0.3, 0.3, 1.0)
                } else {
                    Vec4::ZERO
                }));
            }
        }
    }
    let mut levels = vec![base];
    while levels.len() < 5 {
        let prev = levels.last().unwrap();
        let m = (n >> (levels.len() - 1)) as usize;
        let k = m / 2;
        let mut next = Vec::new();
        for z in 0..k {
            for y in 0..k {
                for x in 0..k {
                    let mut s = Vec4::ZERO;
                    for i in 0..8 {
                        let (dx, dy, dz) = (i & 1, (i >> 1) & 1, i >> 2);
                        s += prev[(2 * x + dx) + m * ((2 * y + dy) + m * (2 * z + dz))];
                    }
                    next.push(round(s / 8.0));
                }
            }
        }
        levels.push(next);
    }
    MipVolume { n, levels }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
struct Probe {
    uvw_aperture: [f32; 4],
    normal: [f32; 4],
    dir: [f32; 4],
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ProbePush {
    steps: i32,
    bias: f32,
    start: f32,
    lod_offset: f32,
    resolution: f32,
    step: f32,
    flags: u32,
    count: u32,
    max_level: f32,
}

#[test]
fn gpu_cone_tracing_agrees_with_the_cpu_model() {
    let ctx = common::context();
    let volume = synthetic_volume();
    let image = Image::new(
        &ctx,
        "synthetic radiance",
        ImageDesc::d3(
            vk::Format::R16G16B16A16_SFLOAT,
            16,
            vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST,
        )
        .mips(5),
    )
    .unwrap();
    let data: Vec<Vec<u8>> = volume
        .levels
        .iter()
        .map(|l| l.iter().flat_map(|v| v.to_array().map(f16::from_f32)).flat_map(|h| h.to_le_bytes()).collect())
        .collect();
    gpu::upload_levels(&ctx, &image, &data, vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL).unwrap();

    let configs = [
        ConeParams {
            steps: 64,
            bias: 1.0,
            start: 1.0,
            lod_offset: 0.0,
            step: 0.5,
            opacity_correction: false,
            self_clamp: false,
        },
        ConeParams {
            steps: 64,
            bias: 1.5,
            start: 1.0,
            lod_offset: -0.79,
            step: 0.3,
            opacity_correction: true,
            self_clamp: true,
        },
    ];
    for params in configs {
        let mut probes = Vec::new();
        for (start, dir, aperture) in [
            (Vec3::new(0.2, 0.5, 0.5), Vec3::X, 0.785),
            (Vec3::new(0.2, 0.5, 0.5), Vec3::new(1.0, 0.3, 0.1), 0.3),
            (Vec3::new(0.1, 0.3, 0.7), Vec3::new(1.0, 0.2, -0.3), 0.05),
            (Vec3::new(0.3, 0.2, 0.4), Vec3::new(-0.2, 1.0, 0.3), 0.785),
            (Vec3::new(0.5, 0.9, 0.2), Vec3::new(0.4, -0.6, 0.5), 1.2),
            (Vec3::new(0.95, 0.5, 0.5), -Vec3::X, 0.6),
            (Vec3::new(0.5, 0.5, 0.05), Vec3::Z, 0.785),
            (Vec3::new(0.4, 0.6, 0.4), Vec3::new(-1.0, 1.0, 0.5), 0.2),
        ] {
            let dir = dir.normalize();
            probes.push(Probe {
                uvw_aperture: start.extend((0.5f32 * aperture).tan()).into(),
                normal: dir.extend(0.0).into(),
                dir: dir.extend(0.0).into(),
            });
        }
        let probe_buf = Buffer::from_slice(&ctx, "probes", vk::BufferUsageFlags::STORAGE_BUFFER, &probes).unwrap();
        let results = Buffer::new(
            &ctx,
            "probe results",
            16 * probes.len() as u64,
            vk::BufferUsageFlags::STORAGE_BUFFER,
            MemoryLocation::GpuToCpu,
        )
        .unwrap();
        let sampler = Sampler::linear_border(&ctx, "probe sampler").unwrap();
        let c = vk::ShaderStageFlags::COMPUTE;
        let set = DescriptorSet::new(
            &ctx,
            "probe",
            &[
                Binding::new(0, vk::DescriptorType::COMBINED_IMAGE_SAMPLER, c),
                Binding::new(1, vk::DescriptorType::STORAGE_BUFFER, c),
                Binding::new(2, vk::DescriptorType::STORAGE_BUFFER, c),
            ],
        )
        .unwrap();
        set.write_sampled(0, image.view.raw, sampler.raw);
        set.write_buffer(1, vk::DescriptorType::STORAGE_BUFFER, &probe_buf);
        set.write_buffer(2, vk::DescriptorType::STORAGE_BUFFER, &results);
        let pipeline =
            Pipeline::compute(&ctx, "cone probe", Stage::new(c, shaders::GI_CONE_PROBE_COMP), &[set.layout], 36)
                .unwrap();
        let flags = (vct::config::CONE_FLAG_OPACITY_CORRECTION * params.opacity_correction as u32)
            | (vct::config::CONE_FLAG_SELF_CLAMP * params.self_clamp as u32);
        let push = ProbePush {
            steps: params.steps,
            bias: params.bias,
            start: params.start,
            lod_offset: params.lod_offset,
            resolution: 16.0,
            step: params.step,
            flags,
            count: probes.len() as u32,
            max_level: (volume.levels.len() - 1) as f32,
        };
        ctx.submit_and_wait("cone probes", |cmd| {
            pipeline.bind(cmd, &[set.raw]);
            pipeline.push(cmd, &push);
            gpu::dispatch(&ctx, cmd, [probes.len() as u32, 1, 1], [vct::config::WORKGROUP_1D, 1, 1]);
            gpu::memory_barrier(
                &ctx,
                cmd,
                (vk::PipelineStageFlags2::COMPUTE_SHADER, vk::AccessFlags2::SHADER_STORAGE_WRITE),
                (vk::PipelineStageFlags2::HOST, vk::AccessFlags2::HOST_READ),
            );
        })
        .unwrap();
        let gpu_out: &[Vec4] = bytemuck::cast_slice(results.read());
        let mut lit = 0;
        for (p, g) in probes.iter().zip(gpu_out) {
            let uvw = Vec4::from(p.uvw_aperture);
            let cpu = volume.trace_cone(
                uvw.truncate(),
                Vec4::from(p.normal).truncate(),
                Vec4::from(p.dir).truncate(),
                uvw.w,
                params,
            );
            let err = (*g - cpu).abs().max_element();
            assert!(err <= 0.01 + 0.01 * cpu.abs().max_element(), "probe {p:?}: GPU {g} vs CPU {cpu}");
            lit += (cpu.x > 0.1) as usize;
        }
        assert!(lit >= 3, "too few probes see the emissive slab for the comparison to mean much");
    }
    common::assert_clean(&ctx);
}

/// Mean linear colour over a small window of pixels around the one that sees `p`.
fn around(scene: &Scene, f: &FrameImages, p: Vec3) -> Vec3 {
    let (x, y) = common::pixel_of(scene, p);
    let mut s = Vec3::ZERO;
    for dy in -1..=1i32 {
        for dx in -1..=1i32 {
            s += common::hdr(f, (x as i32 + dx) as u32, (y as i32 + dy) as u32);
        }
    }
    s / 9.0
}

#[test]
fn cornell_box_shows_colour_bleeding_a_lit_ceiling_and_occlusion() {
    let scene = Scene::embedded_default().unwrap();
    let full = render(scene.clone(), options(View::Full, 64));
    let direct = render(scene.clone(), options(View::Direct, 64));
    let ao = render(scene.clone(), options(View::Ao, 64));
    let redness = |c: Vec3| c.x / c.y.max(1e-6);
    let greenness = |c: Vec3| c.y / c.x.max(1e-6);
    // Floor and back wall near each coloured wall take its colour.
    for (near_red, near_green) in [
        (Vec3::new(-2.4, 0.0, 2.0), Vec3::new(2.4, 0.0, 2.0)),
        (Vec3::new(-2.4, 2.5, -2.75), Vec3::new(2.4, 2.5, -2.75)),
    ] {
        let (r, g) = (around(&scene, &full, near_red), around(&scene, &full, near_green));
        println!("near red {r}, near green {g}");
        assert!(redness(r) > 1.05 * redness(g), "no red bleeding: {r} vs {g}");
        assert!(greenness(g) > 1.05 * greenness(r), "no green bleeding: {g} vs {r}");
    }
    // The ceiling: no direct light reaches it, indirect light does.
    let ceiling = Vec3::new(0.5, 5.5, 1.5);
    let (cf, cd) = (around(&scene, &full, ceiling), around(&scene, &direct, ceiling));
    println!("ceiling full {cf}, direct {cd}");
    assert!(cd.max_element() < 1e-4, "direct light on the ceiling: {cd}");
    assert!(cf.min_element() > 0.01, "ceiling not lit by indirect light: {cf}");
    // Ambient occlusion: darker along the room's edges than mid-wall. The cones run until they
    // end opaque, so in a closed room the open fraction is small everywhere: compare ratios.
    let mid = around(&scene, &ao, Vec3::new(1.2, 3.5, -2.75)).x;
    for corner in [Vec3::new(0.0, 5.45, -2.7), Vec3::new(-2.7, 0.05, -1.5)] {
        let c = around(&scene, &ao, corner).x;
        println!("AO at edge {corner}: {c}, mid-wall {mid}");
        assert!(c < 0.8 * mid, "edge AO {c} vs mid-wall {mid}");
    }
}

#[test]
fn no_light_no_emission_means_black_and_emission_lights_only_its_own_colour() {
    let mut scene = Scene::embedded_default().unwrap();
    scene.lights.clear();
    let black = render(scene.clone(), options(View::Full, 32));
    let max = black.hdr.chunks_exact(4).map(|p| p[0].max(p[1]).max(p[2])).fold(0.0f32, f32::max);
    assert!(max < 1e-6, "light from nowhere: max radiance {max}");
    // Make the left wall emit pure red: red may appear anywhere, green and blue nowhere.
    let red = scene.materials.iter().position(|m| m.name == "red").unwrap();
    scene.materials[red].emissive = Vec3::new(2.0, 0.0, 0.0);
    let lit = render(scene.clone(), options(View::Full, 32));
    let wall = around(&scene, &lit, Vec3::new(-2.75, 2.0, 0.0));
    let floor = around(&scene, &lit, Vec3::new(-1.5, 0.0, 1.5));
    assert!(wall.x >= 2.0 && floor.x > 0.01, "emission {wall}, its indirect light {floor}");
    let gb = lit.hdr.chunks_exact(4).map(|p| p[1].max(p[2])).fold(0.0f32, f32::max);
    assert!(gb < 1e-6, "green/blue light from a red emitter: {gb}");
}

#[test]
fn tessellated_and_rasterized_voxels_give_nearly_the_same_image() {
    use vct::scene::file::Injection;
    // The footprint level rule samples a level finer than the thesis' diameter rule, so the
    // voxelizers' sub-voxel differences show a little more (mean 1.67 measured, 64³; 1.78 with
    // sixteen cones). Injection from the voxels (the default) reads each voxel's own normal and
    // whether its neighbour towards the light is occupied, where the texels only mark the voxel
    // they land in, so it passes more of those differences on (mean 2.22-2.25, p99 12-14).
    for (injection, mean_bar, p99_bar) in [(Injection::Texels, 2.0, 12.0), (Injection::Voxels, 2.5, 16.0)] {
        let mut scene = Scene::embedded_default().unwrap();
        scene.settings.gi.injection = injection;
        same_image_from_both_voxelizers(scene, mean_bar, p99_bar);
    }
}

fn same_image_from_both_voxelizers(scene: Scene, mean_bar: f32, p99_bar: f32) {
    let injection = scene.settings.gi.injection.name();
    let mut tess = options(View::Full, 64);
    tess.method = VoxelizeMethod::tess();
    let a = render(scene.clone(), tess);
    let b = render(scene, options(View::Full, 64));
    let diffs: Vec<f32> = a
        .ldr
        .chunks_exact(4)
        .zip(b.ldr.chunks_exact(4))
        .map(|(p, q)| (0..3).map(|c| (p[c] as f32 - q[c] as f32).abs()).fold(0.0, f32::max))
        .collect();
    let mean = diffs.iter().sum::<f32>() / diffs.len() as f32;
    let mut sorted = diffs.clone();
    sorted.sort_by(f32::total_cmp);
    let p99 = sorted[sorted.len() * 99 / 100];
    println!("tess vs raster, injection from the {injection}: mean |ΔLDR| {mean:.3}, 99th percentile {p99}");
    assert!(mean < mean_bar && p99 <= p99_bar, "injection from the {injection}: mean {mean}, p99 {p99}");
}

#[test]
fn volume_views_show_the_voxels_and_the_radiance_mips() {
    let scene = Scene::embedded_default().unwrap();
    let voxels = render(scene.clone(), options(View::Voxels, 32));
    let wall = around(&scene, &voxels, Vec3::new(-2.75, 2.0, 0.0));
    assert!(wall.x > 0.5 && wall.y < 0.1, "voxel view of the red wall: {wall}");
    let radiance = render(scene.clone(), options(View::Radiance(1), 32));
    let floor = around(&scene, &radiance, Vec3::new(-1.0, 0.0, 2.0));
    let ceiling = around(&scene, &radiance, Vec3::new(0.5, 5.5, 1.5));
    assert!(
        floor.x > 0.1 && ceiling.max_element() < 1e-3,
        "radiance level 1: lit floor {floor}, unlit ceiling {ceiling}"
    );
}

#[test]
fn hardware_coverage_is_a_clear_error_where_the_extension_is_missing() {
    let ctx = common::context();
    if ctx.info.features.conservative_rasterization {
        return; // a device that has it (NVIDIA) builds the pipeline in the other tests' manner
    }
    let mut o = options(View::Full, 32);
    o.method = VoxelizeMethod::raster(Coverage::Hardware);
    let err =
        Renderer::new(&ctx, Scene::embedded_default().unwrap(), o).err().expect("hw coverage must fail on this device");
    assert!(err.to_string().contains("VK_EXT_conservative_rasterization"), "{err}");
}

#[test]
fn deferred_tracing_renders_what_forward_tracing_renders() {
    // The set unturned: with it turned by pixel, deferred shading resolves each pixel's gather
    // from its neighbours' and forward shading cannot (docs/design/cones.md).
    let mut scene = Scene::embedded_default().unwrap();
    scene.settings.gi.turn_cones = false;
    let deferred = render(scene.clone(), options(View::Full, 32));
    let mut o = options(View::Full, 32);
    o.tracing = vct::render::Tracing::Forward;
    let forward = render(scene, o);
    let mut d: Vec<i32> = forward.ldr.iter().zip(&deferred.ldr).map(|(a, b)| (*a as i32 - *b as i32).abs()).collect();
    let mean = d.iter().sum::<i32>() as f32 / d.len() as f32;
    d.sort_unstable();
    let p999 = d[d.len() * 999 / 1000];
    println!("forward vs deferred: mean |ΔLDR| {mean:.4}, 99.9th percentile {p999}, worst {}", d[d.len() - 1]);
    // A few silhouette pixels differ (quad-interpolated vs rebuilt positions); the rest agree.
    assert!(mean < 0.5 && p999 <= 8, "mean {mean}, 99.9th percentile {p999}");
}

/// The temporal blend reprojects its history when a following volume moves: after one whole-voxel
/// step of a converged volume over a still scene, level 0 equals a volume converged at the new
/// place, while the old volume read in place (no reprojection) is far from it.
#[test]
fn temporal_blend_reprojects_history_when_the_volume_moves() {
    let ctx = common::context();
    let mut scene = Scene::embedded_default().unwrap();
    scene.settings.gi.temporal = 0.2;
    let o =
        RenderOptions { follow: Some(vct::render::Follow { extent: 4.0, snap: true }), ..options(View::Indirect, 32) };
    // A centre half a voxel (4 m / 32) off the snapping lattice, so one voxel moves the origin by one.
    let centre = Vec3::new(0.0625, 2.8125, 0.0625);
    let step = Vec3::X * 0.125;
    let level0 = |r: &Renderer| f16s(&r.voxels.read_dense(r.radiance.level0()).unwrap());
    let converged = |at: Vec3| {
        let mut r = Renderer::new(&ctx, scene.clone(), o).unwrap();
        r.follow(at).unwrap();
        for _ in 0..25 {
            r.render().unwrap();
        }
        r
    };
    let mut moved = converged(centre);
    let before = level0(&moved);
    moved.follow(centre + step).unwrap();
    moved.render().unwrap();
    let after = level0(&moved);
    drop(moved);
    let fresh = level0(&converged(centre + step));
    let rel = |a: &[f32], b: &[f32]| {
        let d: f64 = a.iter().zip(b).map(|(x, y)| (x - y).abs() as f64).sum();
        d / b.iter().map(|y| y.abs() as f64).sum::<f64>()
    };
    let (reprojected, in_place) = (rel(&after, &fresh), rel(&before, &fresh));
    println!("level 0 against a volume converged in place: reprojected {reprojected:.4}, not moved {in_place:.4}");
    assert!(in_place > 0.2, "a one-voxel step should change level 0 a lot: {in_place}");
    assert!(reprojected < 0.01, "the reprojected blend should match: {reprojected}");
    common::assert_clean(&ctx);
}
