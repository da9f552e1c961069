//! The scene on the GPU: vertex and index buffers, the material buffer, textures (with mip
//! chains), the diffuse cone set, the frame uniform buffer, and descriptor set 0 that every
//! scene-drawing pass and every voxelizer binds (see `common/frame.glsl`). Below the voxelizers
//! and the render passes: it imports neither.

use std::sync::Arc;

use ash::vk;
use glam::{Mat4, Vec4};

use crate::config;
use crate::error::Result;
use crate::gpu::{
    commands, Binding, Buffer, Context, DescriptorSet, FrameBuffer, Image, ImageDesc, Sampler, VertexLayout,
};
use crate::scene::{Draw, Mesh, Scene, Vertex};

/// Mirrors `Material` in `common/frame.glsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct MaterialGpu {
    pub albedo: [f32; 4],
    pub emissive: [f32; 4],
    pub specular: [f32; 4],
    pub tex: [u32; 4],
}

/// Mirrors `FrameUniforms` in `common/frame.glsl` (filled by `render::frame`).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FrameUniforms {
    pub view_proj: Mat4,
    pub inv_view_proj: Mat4,
    pub camera_pos: Vec4,
    pub viewport: Vec4,
    pub voxel_origin: Vec4,
    pub voxel_grid: Vec4,
    pub cone: Vec4,
    pub cone_model: Vec4,
    pub view: Vec4,
    /// xyz: where this frame's voxel grid origin lies in the previous frame's grid (voxels).
    pub history_shift: Vec4,
    /// xyz: voxels along each axis.
    pub voxel_dims: Vec4,
    /// The directional chains' atlas (render::radiance::AtlasLayout::uniform).
    pub aniso_atlas: Vec4,
    /// x: lights in `lights`.
    pub light_count: Vec4,
    pub lights: [LightGpu; config::MAX_LIGHTS as usize],
    /// Each shadow-map layer's world-to-clip matrix (a point light's six cube faces, +x, -x, +y,
    /// -y, +z, -z; render::frame::shadow_layers).
    pub light_layers: [Mat4; config::MAX_SHADOW_LAYERS as usize],
    /// The previous frame's world-to-clip matrix (screen-space accumulation of indirect light).
    pub previous_view_proj: Mat4,
    /// xy: the pixel of each GI-scale block the diffuse cones trace this frame; z: a history to
    /// accumulate with (1) or none (0) (render::deferred).
    pub gi_jitter: Vec4,
    /// The grid's warp (`voxel::warp::Warp::gpu`; w = 1: none).
    pub voxel_warp: Vec4,
    /// A perspective warp's grid fraction to texture fraction and back (`voxel::warp::Warp::proj`).
    pub voxel_warp_proj: Mat4,
    pub voxel_warp_unproj: Mat4,
    /// A clipmap's levels (`voxel::clipmap::Clipmap::gpu`; x = 0: none).
    pub clip: Vec4,
    pub clip_levels: [Vec4; config::MAX_CLIP_LEVELS as usize],
    /// The scene's bounds (minimum, maximum) in voxels of level 0 from its corner: a level's face
    /// beyond them is open (`voxel::clipmap::Clipmap::open`).
    pub clip_scene: [Vec4; 2],
}

/// One light as the shaders read it (`LightData` in common/frame.glsl).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct LightGpu {
    /// xyz: spot or point position; w: LIGHT_*.
    pub position: Vec4,
    /// xyz: the way light travels.
    pub direction: Vec4,
    /// rgb: intensity (W/sr) or irradiance (W/m²).
    pub color: Vec4,
    /// x, y: inner and outer half-angle (radians); z: shadow texel size (uv); w: first layer.
    pub cone: Vec4,
    /// xyz: an area light's half edges (its corners: position ± half_u ± half_v).
    pub half_u: Vec4,
    pub half_v: Vec4,
}

pub const VERTEX_ATTRIBUTES: [vk::VertexInputAttributeDescription; 4] = [
    vk::VertexInputAttributeDescription { location: 0, binding: 0, format: vk::Format::R32G32B32_SFLOAT, offset: 0 },
    vk::VertexInputAttributeDescription { location: 1, binding: 0, format: vk::Format::R32G32B32_SFLOAT, offset: 12 },
    vk::VertexInputAttributeDescription { location: 2, binding: 0, format: vk::Format::R32G32_SFLOAT, offset: 24 },
    vk::VertexInputAttributeDescription {
        location: 3,
        binding: 0,
        format: vk::Format::R32G32B32A32_SFLOAT,
        offset: 32,
    },
];

pub fn vertex_layout() -> VertexLayout<'static> {
    VertexLayout { stride: std::mem::size_of::<Vertex>() as u32, attributes: &VERTEX_ATTRIBUTES }
}

/// Position, normal and UV only (the voxelizers need no tangent).
pub fn vertex_layout_untangented() -> VertexLayout<'static> {
    VertexLayout { stride: std::mem::size_of::<Vertex>() as u32, attributes: &VERTEX_ATTRIBUTES[..3] }
}

/// A mesh on the GPU: vertex and index buffers and one draw per material.
pub struct MeshBuffers {
    ctx: Arc<Context>,
    pub vertices: Buffer,
    pub indices: Buffer,
    pub draws: Vec<Draw>,
    /// Each draw cut into runs of CLUSTER_TRIANGLES consecutive triangles with their bounds,
    /// for draws that need only what meets a box ([`MeshBuffers::draw_within`]).
    pub clusters: Vec<Cluster>,
}

/// Triangles in a cluster: the clipmap's levels draw, per level, the clusters that meet its box.
/// Measured on Sponza (66445 triangles, the atrium camera, four levels of 64³): runs of 64, 128
/// and 256 triangles in the file's order draw 2.24, 2.4 and 2.67 times the mesh over the four
/// levels, against 4 undivided and 1.94 triangle by triangle (2.14 for 64 in Morton order, which
/// would reorder every pass's triangles); 128 keeps about 520 draws a level.
pub const CLUSTER_TRIANGLES: u32 = 128;

/// A run of one draw's consecutive triangles and the box that holds them.
#[derive(Clone, Copy, Debug)]
pub struct Cluster {
    pub first_index: u32,
    pub index_count: u32,
    pub material: u32,
    pub bounds: crate::scene::Aabb,
}

/// Cuts each of `mesh`'s draws into clusters of at most `size` consecutive triangles.
pub fn clusters(mesh: &Mesh, size: u32) -> Vec<Cluster> {
    let mut out = Vec::new();
    for draw in &mesh.draws {
        let end = draw.first_index + draw.index_count;
        let mut first = draw.first_index;
        while first < end {
            let count = (end - first).min(3 * size.max(1));
            let mut bounds = crate::scene::Aabb::EMPTY;
            for &i in &mesh.indices[first as usize..(first + count) as usize] {
                bounds.grow(glam::Vec3::from(mesh.vertices[i as usize].pos));
            }
            out.push(Cluster { first_index: first, index_count: count, material: draw.material, bounds });
            first += count;
        }
    }
    out
}

impl MeshBuffers {
    pub fn new(ctx: &Arc<Context>, name: &str, mesh: &Mesh) -> Result<Self> {
        let storage = vk::BufferUsageFlags::STORAGE_BUFFER;
        let vertices = commands::upload_buffer(
            ctx,
            &format!("{name} vertices"),
            vk::BufferUsageFlags::VERTEX_BUFFER | storage,
            &mesh.vertices,
        )?;
        let indices = commands::upload_buffer(
            ctx,
            &format!("{name} indices"),
            vk::BufferUsageFlags::INDEX_BUFFER | storage,
            &mesh.indices,
        )?;
        let clusters = clusters(mesh, CLUSTER_TRIANGLES);
        Ok(MeshBuffers { ctx: ctx.clone(), vertices, indices, draws: mesh.draws.clone(), clusters })
    }

    /// Binds the buffers and issues one draw per material, pushing its index and, when given,
    /// binding its textures (one set per material) as set 1.
    pub fn draw(&self, cmd: vk::CommandBuffer, layout: vk::PipelineLayout, material_sets: Option<&DescriptorSet>) {
        self.draw_within(cmd, layout, material_sets, None);
    }

    /// [`Self::draw`], only the clusters that meet `within` when given (a voxelization into a
    /// box: a triangle outside it writes no voxel of it). Consecutive clusters drawn are one draw;
    /// without a box, the draws as they are.
    pub fn draw_within(
        &self,
        cmd: vk::CommandBuffer,
        layout: vk::PipelineLayout,
        material_sets: Option<&DescriptorSet>,
        within: Option<&crate::scene::Aabb>,
    ) {
        let d = &self.ctx.device;
        let mut material = None;
        let mut issue = |first: u32, count: u32, m: u32| unsafe {
            if material != Some(m) {
                d.cmd_push_constants(cmd, layout, vk::ShaderStageFlags::ALL, 0, bytemuck::bytes_of(&m));
                if let Some(sets) = material_sets {
                    let set = [sets.sets[m as usize]];
                    d.cmd_bind_descriptor_sets(cmd, vk::PipelineBindPoint::GRAPHICS, layout, 1, &set, &[]);
                }
                material = Some(m);
            }
            d.cmd_draw_indexed(cmd, count, 1, first, 0, 0);
        };
        unsafe {
            d.cmd_bind_vertex_buffers(cmd, 0, &[self.vertices.raw], &[0]);
            d.cmd_bind_index_buffer(cmd, self.indices.raw, 0, vk::IndexType::UINT32);
        }
        let Some(within) = within else {
            for draw in &self.draws {
                issue(draw.first_index, draw.index_count, draw.material);
            }
            return;
        };
        // Runs of consecutive clusters of one material that meet the box: one draw each.
        let mut run: Option<(u32, u32, u32)> = None;
        for c in self.clusters.iter().filter(|c| c.bounds.overlaps(within)) {
            run = match run {
                Some((first, count, m)) if m == c.material && first + count == c.first_index => {
                    Some((first, count + c.index_count, m))
                }
                Some((first, count, m)) => {
                    issue(first, count, m);
                    Some((c.first_index, c.index_count, c.material))
                }
                None => Some((c.first_index, c.index_count, c.material)),
            };
        }
        if let Some((first, count, m)) = run {
            issue(first, count, m);
        }
    }

    /// Draws `slots` vertices per triangle, without vertex or index buffers (a vertex shader
    /// that reads the mesh as storage: `gl_VertexIndex / slots` is the triangle), one draw per
    /// material as [`MeshBuffers::draw`].
    pub fn draw_slots(
        &self,
        cmd: vk::CommandBuffer,
        layout: vk::PipelineLayout,
        material_sets: &DescriptorSet,
        slots: u32,
    ) {
        let d = &self.ctx.device;
        unsafe {
            for draw in &self.draws {
                d.cmd_push_constants(cmd, layout, vk::ShaderStageFlags::ALL, 0, bytemuck::bytes_of(&draw.material));
                let set = [material_sets.sets[draw.material as usize]];
                d.cmd_bind_descriptor_sets(cmd, vk::PipelineBindPoint::GRAPHICS, layout, 1, &set, &[]);
                d.cmd_draw(cmd, draw.index_count / 3 * slots, 1, draw.first_index / 3 * slots, 0);
            }
        }
    }
}

pub struct SceneGpu {
    pub mesh: MeshBuffers,
    /// The frame uniforms, uploaded by each frame's commands (`Renderer::record`).
    pub uniforms: FrameBuffer,
    /// The surfaces' and the voxel bounce's cone sets (MAX_CONES entries each; the frame
    /// uniforms say how many are used).
    pub cones: Buffer,
    pub cone_count: u32,
    pub bounce_cone_count: u32,
    /// Whether any light is an area light: the shaders that light points are specialized on it
    /// (common/light.glsl, VCT_AREA_LIGHTS), since on lavapipe the polygon's code, run for
    /// every lane whether or not one is an area light, costs spot-lit injection 1.7-2x and the
    /// deferred shading of every pixel a fifth (docs/design/injection.md).
    pub area_lights: bool,
    /// Whether any material reflects specularly (its F0 above zero: a specular colour, or a
    /// metal): without one, the specular cone's code and images are left out of the shading
    /// (common/shading.glsl, VCT_SPECULAR).
    pub specular: bool,
    _materials: Buffer,
    _textures: Vec<Image>,
    _sampler: Sampler,
    /// Set 0: frame uniforms and materials.
    pub set: DescriptorSet,
    /// Set 1: one set of textures per material, bound per draw by [`SceneGpu::draw`].
    pub material_sets: DescriptorSet,
}

fn can_blit_mips(ctx: &Context, format: vk::Format) -> bool {
    let props = unsafe { ctx.instance.get_physical_device_format_properties(ctx.physical, format) };
    props.optimal_tiling_features.contains(
        vk::FormatFeatureFlags::BLIT_SRC
            | vk::FormatFeatureFlags::BLIT_DST
            | vk::FormatFeatureFlags::SAMPLED_IMAGE_FILTER_LINEAR,
    )
}

impl SceneGpu {
    pub fn new(ctx: &Arc<Context>, scene: &Scene) -> Result<Self> {
        let mesh = MeshBuffers::new(ctx, "scene", &scene.mesh)?;

        let mut textures = Vec::new();
        for t in &scene.textures {
            let format = if t.srgb { vk::Format::R8G8B8A8_SRGB } else { vk::Format::R8G8B8A8_UNORM };
            let levels = if can_blit_mips(ctx, format) { 32 - t.width.max(t.height).leading_zeros() } else { 1 };
            let usage =
                vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST | vk::ImageUsageFlags::TRANSFER_SRC;
            let img = Image::new(
                ctx,
                &t.path.display().to_string(),
                ImageDesc::d2(format, t.width, t.height, usage).mips(levels),
            )?;
            commands::upload_texture(ctx, &img, &t.rgba)?;
            textures.push(img);
        }
        let white = Image::new(
            ctx,
            "white texel",
            ImageDesc::d2(
                vk::Format::R8G8B8A8_UNORM,
                1,
                1,
                vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST,
            ),
        )?;
        commands::upload_texture(ctx, &white, &[255, 255, 255, 255])?;

        let flag = |t: Option<usize>| if t.is_some() { config::HAS_TEXTURE } else { config::NO_TEXTURE };
        let materials_gpu: Vec<MaterialGpu> = scene
            .materials
            .iter()
            .map(|m| MaterialGpu {
                albedo: m.albedo.extend(m.metallic).into(),
                emissive: m.emissive.extend(m.roughness).into(),
                specular: m.specular.extend(0.0).into(),
                tex: [flag(m.albedo_texture), flag(m.normal_texture), m.area_light as u32, 0],
            })
            .collect();
        let materials =
            commands::upload_buffer(ctx, "materials", vk::BufferUsageFlags::STORAGE_BUFFER, &materials_gpu)?;
        let uniforms = FrameBuffer::new(
            ctx,
            "frame uniforms",
            std::mem::size_of::<FrameUniforms>() as u64,
            vk::BufferUsageFlags::UNIFORM_BUFFER,
        )?;
        let sampler = Sampler::linear_repeat(ctx, "material sampler")?;
        let gi = &scene.settings.gi;
        let mut cone_count = super::cones::cones(gi.cones).len() as u32;
        let bounce_cone_count = super::cones::cones(gi.bounce_cones).len() as u32;
        let mut cone_data = super::cones::buffer(gi.cones, gi.aperture, gi.bounce_cones);
        if let Some(k) = gi.only_cone {
            if k >= cone_count {
                return Err(crate::error::Error::param(
                    "only_cone",
                    format!("cone {k} of the set {}, which has {cone_count}", gi.cones.name()),
                ));
            }
            cone_data[0] = cone_data[k as usize];
            cone_data[0].dir_weight[3] = 1.0;
            cone_count = 1;
        }
        let cones = Buffer::from_slice(ctx, "diffuse cones", vk::BufferUsageFlags::STORAGE_BUFFER, &cone_data)?;

        let all = vk::ShaderStageFlags::ALL;
        let set = DescriptorSet::new(
            ctx,
            "scene set",
            &[
                Binding::new(0, vk::DescriptorType::UNIFORM_BUFFER, all),
                Binding::new(1, vk::DescriptorType::STORAGE_BUFFER, all),
                Binding::new(2, vk::DescriptorType::STORAGE_BUFFER, all),
            ],
        )?;
        set.write_buffer(0, vk::DescriptorType::UNIFORM_BUFFER, &uniforms.buffer);
        set.write_buffer(1, vk::DescriptorType::STORAGE_BUFFER, &materials);
        set.write_buffer(2, vk::DescriptorType::STORAGE_BUFFER, &cones);
        let sampled = vk::DescriptorType::COMBINED_IMAGE_SAMPLER;
        let frag = vk::ShaderStageFlags::ALL_GRAPHICS;
        let material_sets = DescriptorSet::new_many(
            ctx,
            "material textures",
            &[Binding::new(0, sampled, frag), Binding::new(1, sampled, frag)],
            scene.materials.len() as u32,
        )?;
        for (i, m) in scene.materials.iter().enumerate() {
            let view = |t: Option<usize>| t.map(|t| textures[t].view.raw).unwrap_or(white.view.raw);
            material_sets.write_sampled_at(i, 0, view(m.albedo_texture), sampler.raw);
            material_sets.write_sampled_at(i, 1, view(m.normal_texture), sampler.raw);
        }
        textures.push(white);

        Ok(SceneGpu {
            mesh,
            uniforms,
            cones,
            cone_count,
            bounce_cone_count,
            area_lights: scene.lights.iter().any(crate::scene::Light::is_mesh_emitter),
            specular: scene.materials.iter().any(|m| m.specular.max_element() > 0.0 || m.metallic > 0.0),
            _materials: materials,
            _textures: textures,
            _sampler: sampler,
            set,
            material_sets,
        })
    }

    /// Draws the scene's mesh; `textured` binds each material's textures as set 1.
    pub fn draw(&self, cmd: vk::CommandBuffer, layout: vk::PipelineLayout, textured: bool) {
        self.mesh.draw(cmd, layout, textured.then_some(&self.material_sets));
    }

    /// [`Self::draw`], only the triangles near `within` when given (`MeshBuffers::draw_within`).
    pub fn draw_within(
        &self,
        cmd: vk::CommandBuffer,
        layout: vk::PipelineLayout,
        textured: bool,
        within: Option<&crate::scene::Aabb>,
    ) {
        self.mesh.draw_within(cmd, layout, textured.then_some(&self.material_sets), within);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clusters_cut_each_draw_into_bounded_runs() {
        let mut mesh = Mesh::default();
        for i in 0..1000u32 {
            let x = i as f32;
            for p in [[x, 0.0, 0.0], [x + 0.5, 1.0, 0.0], [x, 0.0, 1.0]] {
                mesh.vertices.push(Vertex { pos: p, ..Default::default() });
            }
            mesh.indices.extend([3 * i, 3 * i + 1, 3 * i + 2]);
        }
        mesh.draws = vec![
            Draw { first_index: 0, index_count: 3 * 300, material: 0 },
            Draw { first_index: 900, index_count: 2100, material: 1 },
        ];
        let c = clusters(&mesh, 128);
        // 300 = 128 + 128 + 44, 700 = 5 × 128 + 60: runs of one draw each, in order, covering all.
        assert_eq!(c.len(), 3 + 6);
        let mut next = 0;
        for k in &c {
            assert_eq!(k.first_index, next);
            assert!(k.index_count <= 3 * 128 && k.index_count.is_multiple_of(3));
            let draw = mesh
                .draws
                .iter()
                .find(|d| (d.first_index..d.first_index + d.index_count).contains(&k.first_index))
                .unwrap();
            assert_eq!(k.material, draw.material);
            assert!(k.first_index + k.index_count <= draw.first_index + draw.index_count);
            // Its box holds its triangles: triangle t spans x in [t, t + 0.5].
            let (t0, t1) = (k.first_index / 3, (k.first_index + k.index_count) / 3 - 1);
            assert_eq!((k.bounds.min.x, k.bounds.max.x), (t0 as f32, t1 as f32 + 0.5));
            next += k.index_count;
        }
        assert_eq!(next, 3000);
    }
}
