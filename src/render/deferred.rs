//! Deferred final shading, the default (`--tracing deferred`; the thesis' forward path is
//! `shade.rs`): a G-buffer pass (depth; albedo with textures applied + material index; shading
//! normal + camera distance), then one compute thread per pixel running the same `shade_surface`
//! (common/shading.glsl) as the forward path. With a GI scale s > 1 the diffuse cones are traced
//! first at one pixel in s² and upsampled edge-aware in the shading pass (the reduced-resolution
//! indirect light engines that ship cone tracing use; shade/deferred.comp), and by default the
//! specular cone with them (`RenderOptions::reduced_specular`). With accumulation on
//! (`--gi-accumulate`) the traced pixel of each block moves frame by frame ([`jitter`]) and a pass
//! of its own, between tracing and shading, lets every pixel keep its last trace in a history
//! reprojected with the camera and rejected on disocclusion: two full-resolution history pairs,
//! ping-ponged.

use std::cell::Cell;
use std::sync::Arc;

use ash::vk;
use glam::Vec4;

use super::radiance::RadianceVolume;
use super::shadow::ShadowPass;
use super::Targets;
use crate::error::Result;
use crate::gpu::{
    self, scope, shaders, Binding, Context, DescriptorSet, GpuTimer, GraphicsDesc, Image, ImageDesc, Pipeline, Sampler,
    Stage,
};
use crate::scene::gpu::{vertex_layout, SceneGpu};

const ALBEDO_FORMAT: vk::Format = vk::Format::R16G16B16A16_SFLOAT;
/// Normal and camera distance: 32-bit, so the rebuilt position is as exact as the forward one.
const NORMAL_FORMAT: vk::Format = vk::Format::R32G32B32A32_SFLOAT;
/// The accumulated diffuse gather (radiance and occlusion), as `diffuse_low`.
const HISTORY_FORMAT: vk::Format = vk::Format::R16G16B16A16_SFLOAT;
/// The surface each history pixel belongs to: its world position's bits and a packed normal.
const SURFACE_FORMAT: vk::Format = vk::Format::R32G32B32A32_UINT;

/// Which pixel of each `scale` × `scale` block the diffuse cones trace on frame `frame`: the
/// blocks' pixels in ordered-dither (Bayer) order, so that consecutive frames lie far apart and
/// every pixel is traced once in `scale`² frames.
pub fn jitter(scale: u32, frame: u64) -> [u32; 2] {
    let cells = scale * scale;
    let k = (frame % cells as u64) as u32;
    // The Bayer matrix: a coordinate's lowest bits decide the coarsest part of the rank.
    let rank = |x: u32, y: u32| {
        let mut v = 0;
        let mut bit = 1;
        while bit < scale {
            let (bx, by) = ((x & bit != 0) as u32, (y & bit != 0) as u32);
            v = v * 4 + [[0, 2], [3, 1]][by as usize][bx as usize];
            bit *= 2;
        }
        v
    };
    (0..cells).map(|i| [i % scale, i / scale]).find(|&[x, y]| rank(x, y) == k).unwrap_or([scale / 2, scale / 2])
}

/// The screen-space accumulation's images: one history and one surface image to read (the
/// previous frame's) and one of each to write, swapped every frame.
struct History {
    gather: [Image; 2],
    surface: [Image; 2],
    /// The specular cone's light, when it is traced with the diffuse cones.
    specular: [Image; 2],
}

pub struct DeferredShadePass {
    ctx: Arc<Context>,
    gbuffer_pipeline: Pipeline,
    shade_pipeline: Pipeline,
    /// The diffuse cones at one pixel in `gi_scale`² (none at scale 1).
    trace_pipeline: Option<Pipeline>,
    /// Their upsampling and accumulation into the history (with accumulation only).
    accumulate_pipeline: Option<Pipeline>,
    /// The split set's resolve over the traced pixels (a split set at a reduced scale only).
    resolve_pipeline: Option<Pipeline>,
    /// Their gather (a 1×1 stand-in at scale 1).
    diffuse_low: Image,
    /// The specular cone's light at the same pixels, when it follows the scale (else 1×1).
    specular_low: Image,
    /// The split set's gathers resolved at the traced pixels (else 1×1).
    diffuse_resolved: Image,
    /// Two sets, one a parity of the frame count: each reads one history pair, writes the other.
    set: DescriptorSet,
    albedo: Image,
    normal: Image,
    _shadow_sampler: Sampler,
    gi_scale: u32,
    /// The accumulation's images (1×1 stand-ins without it).
    history: History,
    accumulate: bool,
    /// Frames recorded that traced: the history's parity, and whether a history exists.
    frames: Cell<u64>,
    /// Frames recorded: the jitter's phase (a settled frame counts, so the frames after it trace
    /// the pixels they would have had every frame traced).
    phase: Cell<u64>,
    /// Consecutive frames whose traced light depends on nothing that changed ([`Self::settle`]).
    still: Cell<u64>,
}

impl DeferredShadePass {
    /// `gi`: the model (its filter, whether the cones turn and split; specialization constants);
    /// `gi_scale`: the diffuse cones run at one pixel in `gi_scale`² (1, 2, 4 or 8); `accumulate`:
    /// screen-space accumulation of them over frames (with `gi_scale` > 1); `reduced_specular`:
    /// the specular cone runs with them (else at every pixel). Where the cone set turns by
    /// pixel (`GiFile::turn_cones`) and every pixel holds a gather of its own (scale 1,
    /// whose cones are then traced into an image of their own, or accumulation) each pixel takes
    /// the mean of its 3×3 neighbours on its surface (`resolved_gather` in shade/deferred.comp),
    /// nine turns of the set.
    #[allow(clippy::too_many_arguments)] // the passes it reads, and five switches
    pub fn new(
        ctx: &Arc<Context>,
        scene: &SceneGpu,
        shadow: &ShadowPass,
        radiance: &RadianceVolume,
        bricks: &crate::voxel::bricks::Bricks,
        targets: &Targets,
        gi: &crate::scene::file::GiFile,
        gi_scale: u32,
        accumulate: bool,
        reduced_specular: bool,
        grid: crate::gpu::GridSpec,
    ) -> Result<Self> {
        let anisotropic = gi.filter == crate::scene::file::Filter::Aniso;
        let turned = gi.turn_cones;
        if !matches!(gi_scale, 1 | 2 | 4 | 8) {
            return Err(crate::Error::param("gi-scale", format!("must be 1, 2, 4 or 8, got {gi_scale}")));
        }
        if accumulate && gi_scale == 1 {
            return Err(crate::Error::param(
                "gi-accumulate",
                "needs --gi-scale 2, 4 or 8: at full resolution every pixel is traced every frame",
            ));
        }
        let usage = vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::STORAGE;
        let albedo =
            Image::new(ctx, "gbuffer albedo", ImageDesc::d2(ALBEDO_FORMAT, targets.width, targets.height, usage))?;
        let normal =
            Image::new(ctx, "gbuffer normal", ImageDesc::d2(NORMAL_FORMAT, targets.width, targets.height, usage))?;
        let mut desc = GraphicsDesc::new(
            "gbuffer",
            vec![
                Stage::new(vk::ShaderStageFlags::VERTEX, shaders::SCENE_SCENE_VERT).spec(&[0]),
                Stage::new(vk::ShaderStageFlags::FRAGMENT, shaders::SHADE_GBUFFER_FRAG),
            ],
        );
        desc.set_layouts = vec![scene.set.layout, scene.material_sets.layout];
        desc.push_constant_size = 4;
        desc.vertex = Some(vertex_layout());
        desc.depth_format = Targets::DEPTH_FORMAT;
        desc.depth_test = true;
        desc.depth_write = true;
        desc.color_formats = vec![ALBEDO_FORMAT, NORMAL_FORMAT];
        let gbuffer_pipeline = Pipeline::graphics(ctx, &desc)?;

        let c = vk::ShaderStageFlags::COMPUTE;
        let sampled = vk::DescriptorType::COMBINED_IMAGE_SAMPLER;
        let storage = vk::DescriptorType::STORAGE_IMAGE;
        let set = DescriptorSet::new_many(
            ctx,
            "deferred shade",
            &[
                Binding::new(0, sampled, c),
                Binding::new(1, sampled, c),
                Binding::new(2, storage, c),
                Binding::new(3, storage, c),
                Binding::new(4, storage, c),
                Binding::new(5, sampled, c),
                Binding::new(6, sampled, c),
                Binding::new(7, sampled, c),
                Binding::new(8, vk::DescriptorType::STORAGE_BUFFER, c),
                Binding::new(9, storage, c),
                Binding::new(10, storage, c),
                Binding::new(11, storage, c),
                Binding::new(12, storage, c),
                Binding::new(13, storage, c),
                Binding::new(14, storage, c),
                Binding::new(15, storage, c),
                Binding::new(16, storage, c),
                Binding::new(17, storage, c),
            ],
            2,
        )?;
        let resolve = turned && (gi_scale == 1 || accumulate);
        // Split among 2×2 pixels where every pixel traces each frame (the resolve then gathers
        // each quarter of the set from the pixels that traced it).
        // (A cone drawn alone, `GiFile::only_cone`, is drawn at every pixel.) At a reduced scale
        // the traced pixels resolve the split set among themselves, in a pass of their own; not
        // with accumulation, whose still view becomes every pixel's own trace of the whole set
        // (a resolve over blocks would blur it).
        let split = turned && gi.split_cones && gi.only_cone.is_none() && (gi_scale == 1 || !accumulate);
        let split_reduced = split && gi_scale > 1;
        let (lw, lh) = if gi_scale > 1 || resolve {
            (targets.width.div_ceil(gi_scale), targets.height.div_ceil(gi_scale))
        } else {
            (1, 1)
        };
        let low = |name: &str, (w, h)| {
            Image::new(ctx, name, ImageDesc::d2(vk::Format::R16G16B16A16_SFLOAT, w, h, vk::ImageUsageFlags::STORAGE))
        };
        // A scene whose materials reflect no specular light has no specular cone to trace.
        let reduced_specular = reduced_specular && gi_scale > 1 && scene.specular;
        let diffuse_low = low("diffuse gather (reduced)", (lw, lh))?;
        let specular_low = low("specular cone (reduced)", if reduced_specular { (lw, lh) } else { (1, 1) })?;
        let diffuse_resolved = low("diffuse gather (resolved)", if split_reduced { (lw, lh) } else { (1, 1) })?;
        let (hw, hh) = if accumulate { (targets.width, targets.height) } else { (1, 1) };
        let keep = vk::ImageUsageFlags::STORAGE | vk::ImageUsageFlags::TRANSFER_DST;
        let image = |name: &str, format, (w, h)| Image::new(ctx, name, ImageDesc::d2(format, w, h, keep));
        let (full, spec) = ((hw, hh), if reduced_specular { (hw, hh) } else { (1, 1) });
        let history = History {
            gather: [
                image("diffuse history a", HISTORY_FORMAT, full)?,
                image("diffuse history b", HISTORY_FORMAT, full)?,
            ],
            surface: [
                image("history surface a", SURFACE_FORMAT, full)?,
                image("history surface b", SURFACE_FORMAT, full)?,
            ],
            specular: [
                image("specular history a", HISTORY_FORMAT, spec)?,
                image("specular history b", HISTORY_FORMAT, spec)?,
            ],
        };
        let shadow_sampler = Sampler::shadow(ctx, "deferred shadow sampler")?;
        for i in 0..2 {
            set.write_sampled_at(i, 0, shadow.map.view.raw, shadow_sampler.raw);
            set.write_images_at(i, 1, sampled, &[radiance.sampled_info()]);
            set.write_images_at(i, 5, sampled, &[radiance.aniso_info()]);
            set.write_images_at(i, 6, sampled, &[radiance.moment_info()]);
            set.write_images_at(i, 7, sampled, &[radiance.chain_info()]);
            set.write_buffer_at(i, 8, vk::DescriptorType::STORAGE_BUFFER, &bricks.table);
            set.write_storage_at(i, 2, albedo.view.raw);
            set.write_storage_at(i, 3, normal.view.raw);
            set.write_storage_at(i, 4, targets.hdr.view.raw);
            set.write_storage_at(i, 9, diffuse_low.view.raw);
            // Set i reads pair i and writes pair 1 - i.
            set.write_storage_at(i, 10, history.gather[i].view.raw);
            set.write_storage_at(i, 11, history.gather[1 - i].view.raw);
            set.write_storage_at(i, 12, history.surface[i].view.raw);
            set.write_storage_at(i, 13, history.surface[1 - i].view.raw);
            set.write_storage_at(i, 14, specular_low.view.raw);
            set.write_storage_at(i, 17, diffuse_resolved.view.raw);
            set.write_storage_at(i, 15, history.specular[i].view.raw);
            set.write_storage_at(i, 16, history.specular[1 - i].view.raw);
        }
        let [aniso, sparse, resident] = bricks.spec(anisotropic as u32);
        let layouts = [scene.set.layout, scene.material_sets.layout, set.layout];
        let pipeline = |name: &str, pass: u32| {
            let spec = [
                aniso,
                sparse,
                resident,
                gi_scale,
                pass,
                accumulate as u32,
                reduced_specular as u32,
                scene.area_lights as u32,
                scene.specular as u32,
                resolve as u32,
                split as u32,
            ];
            Pipeline::compute(
                ctx,
                name,
                Stage::new(c, shaders::SHADE_DEFERRED_COMP).spec(&spec).grid(grid),
                &layouts,
                0,
            )
        };
        let shade_pipeline = pipeline("deferred shade", 0)?;
        let trace_pipeline = (gi_scale > 1 || resolve).then(|| pipeline("diffuse cones (reduced)", 1)).transpose()?;
        // A pass of its own: in the shading pass, the accumulation's code (even where it does not
        // run) would make lavapipe's shading 2.2x slower (1280x720, scale 4: 777 -> 1766 ms).
        let accumulate_pipeline = accumulate.then(|| pipeline("diffuse accumulation", 2)).transpose()?;
        let resolve_pipeline = split_reduced.then(|| pipeline("split cones' resolve", 3)).transpose()?;
        Ok(DeferredShadePass {
            ctx: ctx.clone(),
            gbuffer_pipeline,
            shade_pipeline,
            trace_pipeline,
            accumulate_pipeline,
            resolve_pipeline,
            diffuse_low,
            specular_low,
            diffuse_resolved,
            set,
            albedo,
            normal,
            _shadow_sampler: shadow_sampler,
            gi_scale,
            history,
            accumulate,
            frames: Cell::new(0),
            phase: Cell::new(0),
            still: Cell::new(0),
        })
    }

    /// Whether this frame traces the same light as the last: the same uniforms but the jitter,
    /// and the same volume (the renderer's reuse). Counts the frames since the last change.
    pub fn settle(&self, unchanged: bool) {
        self.still.set(if unchanged { self.still.get() + 1 } else { 0 });
    }

    /// A still view whose every pixel holds its own trace of what it shows now: the `gi_scale`²
    /// frames since the last change each traced one pixel of every block. Tracing again would
    /// give each pixel the same value, and the history, reprojected onto itself, would not
    /// change, so the frame skips the trace and the accumulation and shades from the history
    /// last written: the same image (tests/gi_accumulate.rs). Measured (lavapipe, Cornell
    /// 1280x720, scale 8, 64³): a still frame of 225-240 ms (trace 86-90, accumulate 62-65) takes
    /// 77 ms once settled, 64 frames after the last change; a frame that moves pays the whole.
    ///
    /// Without accumulation the traced pixels are the same every frame, so one still frame after
    /// a traced one suffices: the gather images (the split set's partial gathers at full
    /// resolution, or the reduced trace) already hold what tracing again would write.
    pub fn settled(&self) -> bool {
        let needed = if self.accumulate { u64::from(self.gi_scale * self.gi_scale) } else { 1 };
        self.trace_pipeline.is_some() && self.frames.get() > 0 && self.still.get() >= needed
    }

    /// This frame's `gi_jitter` uniform: the traced pixel of each block (its centre without
    /// accumulation), and whether a history exists to accumulate with.
    pub fn jitter_uniform(&self) -> Vec4 {
        let s = self.gi_scale;
        let [x, y] = if self.accumulate { jitter(s, self.phase.get()) } else { [s / 2, s / 2] };
        Vec4::new(x as f32, y as f32, (self.accumulate && self.frames.get() > 0) as u32 as f32, 0.0)
    }

    /// Depth and G-buffer in one geometry pass (it replaces the depth prepass).
    pub fn record_gbuffer(&self, cmd: vk::CommandBuffer, scene: &SceneGpu, targets: &Targets) {
        let ctx = &self.ctx;
        gpu::discard_to_depth(ctx, cmd, &targets.depth, scope::COMPUTE_READ);
        for img in [&self.albedo, &self.normal] {
            gpu::image_barrier(
                ctx,
                cmd,
                img,
                vk::ImageLayout::UNDEFINED,
                vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
                scope::COMPUTE_READ,
                scope::COLOR_WRITE,
            );
        }
        let color: Vec<_> = [&self.albedo, &self.normal]
            .iter()
            .map(|img| {
                vk::RenderingAttachmentInfo::default()
                    .image_view(img.view.raw)
                    .image_layout(vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL)
                    .load_op(vk::AttachmentLoadOp::CLEAR)
                    .store_op(vk::AttachmentStoreOp::STORE)
            })
            .collect();
        gpu::render_multi(
            ctx,
            cmd,
            &color,
            Some((&targets.depth, vk::AttachmentLoadOp::CLEAR)),
            targets.width,
            targets.height,
            || {
                self.gbuffer_pipeline.bind(cmd, &[scene.set.raw]);
                scene.draw(cmd, self.gbuffer_pipeline.layout, true);
            },
        );
        for img in [&self.albedo, &self.normal] {
            gpu::image_barrier(
                ctx,
                cmd,
                img,
                vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
                vk::ImageLayout::GENERAL,
                scope::COLOR_WRITE,
                scope::COMPUTE_READ,
            );
        }
    }

    /// One compute thread per pixel shades into `targets.hdr` (left in GENERAL); the reduced
    /// tracing and the accumulation before it are timed as spans of their own in `timer`.
    pub fn record_shade(&self, cmd: vk::CommandBuffer, scene: &SceneGpu, targets: &Targets, timer: &GpuTimer) {
        let ctx = &self.ctx;
        targets.hdr_for_compute(ctx, cmd);
        let rw = scope::COMPUTE_RW;
        let settled = self.settled();
        // Settled, the gathers the last traced frame wrote are this frame's: kept, not discarded.
        let from = if settled { vk::ImageLayout::GENERAL } else { vk::ImageLayout::UNDEFINED };
        for low in [&self.diffuse_low, &self.specular_low, &self.diffuse_resolved] {
            gpu::image_barrier(ctx, cmd, low, from, vk::ImageLayout::GENERAL, rw, rw);
        }
        let frames = self.frames.get();
        self.phase.set(self.phase.get() + 1);
        // Settled, the set that wrote the history last ((frames - 1) % 2): its output is this frame's.
        let set = self.set.sets[((frames + u64::from(settled)) % 2) as usize];
        if !settled {
            self.record_traced(cmd, scene, targets, timer, frames, set);
        }
        self.shade_pipeline.bind(cmd, &[scene.set.raw]);
        self.shade_pipeline.bind_set(cmd, 2, set);
        timer.span(cmd, "shade pixels", || targets.dispatch_per_pixel(ctx, cmd));
        gpu::memory_barrier(ctx, cmd, scope::COMPUTE_RW, scope::COMPUTE_RW);
    }

    /// The reduced trace and the accumulation of a frame that traces (`frames` the frames traced
    /// before it), into descriptor set `set`.
    fn record_traced(
        &self,
        cmd: vk::CommandBuffer,
        scene: &SceneGpu,
        targets: &Targets,
        timer: &GpuTimer,
        frames: u64,
        set: vk::DescriptorSet,
    ) {
        let (ctx, rw) = (&self.ctx, scope::COMPUTE_RW);
        self.frames.set(frames + 1);
        if frames == 0 {
            // No surface stored: the first frame finds no history (and every image is GENERAL).
            let h = &self.history;
            for img in h.gather.iter().chain(&h.surface).chain(&h.specular) {
                gpu::clear_to_general(ctx, cmd, img, rw);
            }
            gpu::memory_barrier(ctx, cmd, scope::CLEAR_WRITE, rw);
        }
        // The trace, then the split set's resolve, each over the traced pixels.
        for (pipeline, name) in [(&self.trace_pipeline, "trace"), (&self.resolve_pipeline, "resolve")] {
            let Some(p) = pipeline else { continue };
            p.bind(cmd, &[scene.set.raw]);
            p.bind_set(cmd, 2, set);
            let (w, h) = (self.diffuse_low.desc.extent.width, self.diffuse_low.desc.extent.height);
            let local = crate::config::WORKGROUP_2D;
            timer.span(cmd, name, || gpu::dispatch(ctx, cmd, [w, h, 1], [local, local, 1]));
            gpu::memory_barrier(ctx, cmd, rw, rw);
        }
        if let Some(accumulate) = &self.accumulate_pipeline {
            accumulate.bind(cmd, &[scene.set.raw]);
            accumulate.bind_set(cmd, 2, set);
            timer.span(cmd, "accumulate", || targets.dispatch_per_pixel(ctx, cmd));
            gpu::memory_barrier(ctx, cmd, rw, rw);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::jitter;

    #[test]
    fn the_jitter_visits_every_pixel_of_a_block_once_a_cycle_and_far_from_the_last() {
        for scale in [2u32, 4, 8] {
            let cycle: Vec<[u32; 2]> = (0..(scale * scale) as u64).map(|f| jitter(scale, f)).collect();
            let mut seen = cycle.clone();
            seen.sort();
            seen.dedup();
            assert_eq!(seen.len(), (scale * scale) as usize, "scale {scale}: {cycle:?}");
            assert!(cycle.iter().all(|p| p[0] < scale && p[1] < scale));
            assert_eq!(jitter(scale, (scale * scale) as u64), cycle[0], "the cycle repeats");
            // Ordered dither: the first four frames fall in the four quadrants of the block, and
            // the first two lie half a block apart on each axis.
            let mut quadrants: Vec<[u32; 2]> = cycle[..4].iter().map(|p| p.map(|c| c / (scale / 2))).collect();
            quadrants.sort();
            quadrants.dedup();
            assert_eq!(quadrants.len(), 4, "scale {scale}: {cycle:?}");
            assert_eq!([cycle[1][0].abs_diff(cycle[0][0]), cycle[1][1].abs_diff(cycle[0][1])], [scale / 2; 2]);
        }
    }
}
