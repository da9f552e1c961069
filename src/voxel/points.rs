//! Point-based voxelizer: "imperfect volumes" (Mavridis & Papaioannou 2011, §3.1). Sample
//! points are scattered over every triangle at a density in points per voxel area (at least one
//! per triangle), once, when the volume is built; each frame a vertex shader (rasterizer off,
//! point list) writes the voxel each point falls in, with the same averaging as the other two
//! voxelizers. A point lies on its triangle, so every voxel it writes is one the triangle
//! touches: precision is exact, and recall follows the density (a voxel the triangle only
//! grazes holds little of its area and gets no point).
//!
//! The points come from one of two sources ([`PointSource`]): scattered on the CPU when the
//! volume is built (a buffer of one vertex a point, the default: measured faster), or generated
//! each frame by the vertex shader from the mesh, big triangles split at load to a bounded
//! number of points, as the paper advises, rather than amplified at run time.
//!
//! Refinement (§3.2, [`Refine`]): the surface the camera sees is re-projected into the volume,
//! pixel by pixel, filling the voxels the points left empty there, so that what the camera
//! sees has no holes. It renders the scene from the camera in the voxel parameters
//! ([`super::Voxelizer::set_camera`]): a depth pass, then the pixels whose depth equals it.

use std::sync::Arc;

use ash::vk;
use glam::{Vec2, Vec3, Vec4};

use super::subdivide::subdivide_until;
use super::volume::voxel_write_scope;
use super::{params_for, voxel_set, ParamsUbo, VoxelGrid, VoxelVolume};
use crate::config;
use crate::error::{Error, Result};
use crate::gpu::{
    self, scope, shaders, Attachments, Binding, Context, DescriptorSet, GraphicsDesc, Image, ImageDesc, Pipeline, Stage,
};
use crate::scene::gpu::{vertex_layout_untangented, MeshBuffers, SceneGpu};
use crate::scene::{Draw, Mesh, Scene, Vertex};

/// Sample points per voxel area (a triangle of area A gets ceil(density · A / voxel²), at
/// least one). Chosen by measurement (docs/design/voxelizers.md).
pub const DEFAULT_POINT_DENSITY: f32 = 4.0;

/// More points than this is refused: the buffer would pass 400 MiB.
pub const MAX_POINTS: u64 = 1 << 23;

/// The plastic constant's R2 sequence (Roberts 2018): well spread points in the unit square for
/// any count, so a triangle's N points are stratified without a grid of N cells.
fn r2(i: u32, offset: Vec2) -> Vec2 {
    const G: f64 = 1.324_717_957_244_746;
    let a = Vec2::new((1.0 / G) as f32, (1.0 / (G * G)) as f32);
    let p = offset + a * i as f32;
    p - p.floor()
}

/// A hash of the triangle's index to a rotation of the sequence (Cranley–Patterson), so that
/// neighbouring triangles do not place their points alike.
fn rotation(t: u32) -> Vec2 {
    let h = |mut x: u32| {
        x ^= x >> 16;
        x = x.wrapping_mul(0x7feb_352d);
        x ^= x >> 15;
        x = x.wrapping_mul(0x846c_a68b);
        x ^= x >> 16;
        (x >> 8) as f32 / (1u32 << 24) as f32
    };
    Vec2::new(h(2 * t), h(2 * t + 1))
}

/// How many points a triangle of `area` gets at `density` points per `voxel`².
pub fn points_for(area: f32, voxel: f32, density: f32) -> u32 {
    let n = (density * area / (voxel * voxel)).ceil();
    if n.is_finite() {
        n.clamp(1.0, u32::MAX as f32) as u32
    } else {
        1
    }
}

/// The sample points of every triangle of `mesh` at `density` points per voxel area of `grid`,
/// as a mesh of points (one vertex each: position, interpolated normal and UV; indices in
/// order; one draw per material, as the mesh's). Zero-area triangles get none: they cover no
/// voxel a point could find.
pub fn scatter(mesh: &Mesh, grid: &VoxelGrid, density: f32) -> Result<Mesh> {
    if !(density.is_finite() && density > 0.0) {
        return Err(Error::param(
            "point-density",
            format!("must be a positive number of points per voxel area, got {density}"),
        ));
    }
    let mut total = 0u64;
    for t in 0..mesh.triangle_count() {
        let [a, b, c] = mesh.triangle(t);
        let area = 0.5 * (b - a).cross(c - a).length();
        if area > 0.0 {
            total += points_for(area, grid.voxel, density) as u64;
        }
    }
    if total > MAX_POINTS {
        return Err(Error::param(
            "point-density",
            format!("{density} points per voxel area makes {total} points, more than {MAX_POINTS}: lower it"),
        ));
    }
    let mut vertices = Vec::with_capacity(total as usize);
    let mut draws = Vec::with_capacity(mesh.draws.len());
    for draw in &mesh.draws {
        let first = vertices.len() as u32;
        let range = draw.first_index as usize..(draw.first_index + draw.index_count) as usize;
        for (k, tri) in mesh.indices[range].chunks_exact(3).enumerate() {
            let v = [0, 1, 2].map(|i| mesh.vertices[tri[i] as usize]);
            let p = v.map(|x| Vec3::from(x.pos));
            let area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length();
            if area.is_nan() || area <= 0.0 {
                continue;
            }
            let offset = rotation(draw.first_index / 3 + k as u32);
            for i in 0..points_for(area, grid.voxel, density) {
                // The unit square folded onto the triangle (area-preserving).
                let mut s = r2(i, offset);
                if s.x + s.y > 1.0 {
                    s = Vec2::ONE - s;
                }
                let w = [1.0 - s.x - s.y, s.x, s.y];
                let mix3 = |f: fn(&Vertex) -> [f32; 3]| -> [f32; 3] {
                    (Vec3::from(f(&v[0])) * w[0] + Vec3::from(f(&v[1])) * w[1] + Vec3::from(f(&v[2])) * w[2]).into()
                };
                let uv = Vec2::from(v[0].uv) * w[0] + Vec2::from(v[1].uv) * w[1] + Vec2::from(v[2].uv) * w[2];
                vertices.push(Vertex {
                    pos: mix3(|x| x.pos),
                    normal: mix3(|x| x.normal),
                    uv: uv.into(),
                    tangent: Vec4::ZERO.into(),
                });
            }
        }
        let count = vertices.len() as u32 - first;
        if count > 0 {
            draws.push(Draw { first_index: first, index_count: count, material: draw.material });
        }
    }
    let indices = (0..vertices.len() as u32).collect();
    Ok(Mesh { vertices, indices, draws, bounds: mesh.bounds })
}

/// The refinement's depth target and its two pipelines (refine.vert for both).
pub struct Refine {
    depth: Image,
    depth_pass: Pipeline,
    fill: Pipeline,
}

/// The refinement's depth format.
const REFINE_DEPTH: vk::Format = vk::Format::D32_SFLOAT;

impl Refine {
    fn new(
        ctx: &Arc<Context>,
        scene: &Scene,
        scene_gpu: &SceneGpu,
        set: &DescriptorSet,
        spec: &[u32],
        grid: crate::gpu::GridSpec,
    ) -> Result<Self> {
        let (w, h) = (scene.camera.width, scene.camera.height);
        let depth = Image::new(
            ctx,
            "refinement depth",
            ImageDesc::d2(REFINE_DEPTH, w, h, vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT),
        )?;
        let vert = || Stage::new(vk::ShaderStageFlags::VERTEX, shaders::VOXELIZE_REFINE_VERT).spec(spec).grid(grid);
        let layouts = vec![scene_gpu.set.layout, scene_gpu.material_sets.layout, set.layout];
        let mut desc = GraphicsDesc::new("refinement depth", vec![vert()]);
        desc.set_layouts = layouts.clone();
        desc.push_constant_size = 4;
        desc.vertex = Some(vertex_layout_untangented());
        desc.depth_format = REFINE_DEPTH;
        desc.depth_test = true;
        desc.depth_write = true;
        let depth_pass = Pipeline::graphics(ctx, &desc)?;
        let mut desc = GraphicsDesc::new(
            "refinement",
            vec![
                vert(),
                Stage::new(vk::ShaderStageFlags::FRAGMENT, shaders::VOXELIZE_REFINE_FRAG).spec(spec).grid(grid),
            ],
        );
        desc.set_layouts = layouts;
        desc.push_constant_size = 4;
        desc.vertex = Some(vertex_layout_untangented());
        desc.depth_format = REFINE_DEPTH;
        desc.depth_test = true;
        desc.depth_compare = vk::CompareOp::EQUAL;
        let fill = Pipeline::graphics(ctx, &desc)?;
        Ok(Refine { depth, depth_pass, fill })
    }

    fn record(&self, ctx: &Context, cmd: vk::CommandBuffer, scene_gpu: &SceneGpu, set: &DescriptorSet) {
        gpu::discard_to_depth(ctx, cmd, &self.depth, scope::DEPTH_RW);
        let (width, height) = (self.depth.desc.extent.width, self.depth.desc.extent.height);
        let att = |load| Attachments { color: None, depth: Some((&self.depth, load)), width, height };
        gpu::render(ctx, cmd, att(vk::AttachmentLoadOp::CLEAR), || {
            self.depth_pass.bind(cmd, &[scene_gpu.set.raw]);
            self.depth_pass.bind_set(cmd, 2, set.raw);
            scene_gpu.mesh.draw(cmd, self.depth_pass.layout, None);
        });
        gpu::memory_barrier(ctx, cmd, scope::DEPTH_RW, scope::DEPTH_RW);
        // The points' writes come first: the fill only takes voxels they left empty.
        gpu::memory_barrier(ctx, cmd, voxel_write_scope(), voxel_write_scope());
        gpu::render(ctx, cmd, att(vk::AttachmentLoadOp::LOAD), || {
            self.fill.bind(cmd, &[scene_gpu.set.raw]);
            self.fill.bind_set(cmd, 2, set.raw);
            scene_gpu.draw(cmd, self.fill.layout, true);
        });
    }
}

/// Where the sample points come from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum PointSource {
    /// Scattered on the CPU when the volume is built, into a buffer of one vertex a point.
    Load,
    /// Generated each frame by the vertex shader from the mesh (points_gen.vert), big
    /// triangles split at load to POINTS_PER_TRIANGLE points at most.
    Gpu,
}

/// The chosen source (docs/design/voxelizers.md: scattering at load is faster at every size
/// measured, for a buffer of 48 bytes a point).
pub const DEFAULT_POINT_SOURCE: PointSource = PointSource::Load;

/// The points, as each source keeps them.
enum Points {
    Buffer(MeshBuffers),
    /// The mesh with its big triangles split, read as storage (set 3).
    Generated {
        mesh: MeshBuffers,
        set: DescriptorSet,
    },
}

pub struct PointsVoxelizer {
    ctx: Arc<Context>,
    pipeline: Pipeline,
    pub(crate) set: DescriptorSet,
    pub(crate) params: ParamsUbo,
    points: Option<Points>,
    /// Points scattered at load, or triangles split for generation.
    count: usize,
    density: f32,
    source: PointSource,
    refine: Option<Refine>,
}

const _: () = assert!(std::mem::size_of::<Vertex>() == 4 * config::VERTEX_FLOATS as usize);

/// Whether a triangle of corners `p` fits the slots of the GPU source at `density` on `grid`.
fn fits_slots(p: [Vec3; 3], grid: &VoxelGrid, density: f32) -> bool {
    let area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length();
    // With a margin: the GPU computes the area in f32 and rounds the count up.
    area.is_nan() || points_for(area * 1.001, grid.voxel, density) <= config::POINTS_PER_TRIANGLE
}

impl PointsVoxelizer {
    pub fn new(
        ctx: &Arc<Context>,
        scene: &Scene,
        scene_gpu: &SceneGpu,
        volume: &VoxelVolume,
        density: f32,
        source: PointSource,
        refine: bool,
    ) -> Result<Self> {
        let mut params = params_for(&volume.grid, 0, 1.0, 1.0, 1.0);
        params.tess[3] = density;
        let (set, params_buffer) = voxel_set(ctx, volume, &params)?;
        let spec = volume.bricks.spec(0);
        let layouts = vec![scene_gpu.set.layout, scene_gpu.material_sets.layout, set.layout];
        let (points, count, pipeline) = match source {
            PointSource::Load => {
                let points = scatter(&scene.mesh, &volume.grid, density)?;
                let count = points.vertices.len();
                // An empty buffer cannot be created: a scene of degenerate triangles has none.
                let points = (count > 0)
                    .then(|| MeshBuffers::new(ctx, "voxelizer points", &points))
                    .transpose()?
                    .map(Points::Buffer);
                let mut desc = GraphicsDesc::new(
                    "points voxelizer",
                    vec![Stage::new(vk::ShaderStageFlags::VERTEX, shaders::VOXELIZE_POINTS_VERT)
                        .spec(&spec)
                        .grid(volume.grid.spec())],
                );
                desc.set_layouts = layouts;
                desc.vertex = Some(vertex_layout_untangented());
                (points, count, Self::pipeline(ctx, desc)?)
            }
            PointSource::Gpu => {
                if !(density.is_finite() && density > 0.0) {
                    return Err(Error::param(
                        "point-density",
                        format!("must be a positive number of points per voxel area, got {density}"),
                    ));
                }
                let (mesh, _) = subdivide_until(&scene.mesh, |p| fits_slots(p, &volume.grid, density));
                let count = mesh.triangle_count();
                let storage = |b| Binding::new(b, vk::DescriptorType::STORAGE_BUFFER, vk::ShaderStageFlags::VERTEX);
                let mesh_set = DescriptorSet::new(ctx, "points mesh", &[storage(0), storage(1)])?;
                let mut desc = GraphicsDesc::new(
                    "points voxelizer (generating)",
                    vec![Stage::new(vk::ShaderStageFlags::VERTEX, shaders::VOXELIZE_POINTS_GEN_VERT)
                        .spec(&spec)
                        .grid(volume.grid.spec())],
                );
                desc.set_layouts = layouts.into_iter().chain([mesh_set.layout]).collect();
                let points = if count > 0 {
                    let mesh = MeshBuffers::new(ctx, "voxelizer split mesh", &mesh)?;
                    mesh_set.write_buffer(0, vk::DescriptorType::STORAGE_BUFFER, &mesh.vertices);
                    mesh_set.write_buffer(1, vk::DescriptorType::STORAGE_BUFFER, &mesh.indices);
                    Some(Points::Generated { mesh, set: mesh_set })
                } else {
                    None
                };
                (points, count, Self::pipeline(ctx, desc)?)
            }
        };
        // The scene's own camera until the renderer says otherwise (a sparse pool's census
        // then sees what the first frame will).
        params_buffer.set_camera(scene.camera.view_proj(&scene.mesh.bounds));
        let refine = refine.then(|| Refine::new(ctx, scene, scene_gpu, &set, &spec, volume.grid.spec())).transpose()?;
        Ok(PointsVoxelizer {
            ctx: ctx.clone(),
            pipeline,
            set,
            params: params_buffer,
            points,
            count,
            density,
            source,
            refine,
        })
    }

    /// A point list with no rasterization: the vertex stage writes the voxels.
    fn pipeline(ctx: &Arc<Context>, mut desc: GraphicsDesc) -> Result<Pipeline> {
        desc.push_constant_size = 4;
        desc.topology = vk::PrimitiveTopology::POINT_LIST;
        desc.rasterizer_discard = true;
        Pipeline::graphics(ctx, &desc)
    }

    pub fn record(&self, cmd: vk::CommandBuffer, scene_gpu: &SceneGpu) {
        if let Some(points) = &self.points {
            let att = Attachments { color: None, depth: None, width: 1, height: 1 };
            gpu::render(&self.ctx, cmd, att, || {
                self.pipeline.bind(cmd, &[scene_gpu.set.raw]);
                self.pipeline.bind_set(cmd, 2, self.set.raw);
                match points {
                    Points::Buffer(b) => b.draw(cmd, self.pipeline.layout, Some(&scene_gpu.material_sets)),
                    Points::Generated { mesh, set } => {
                        self.pipeline.bind_set(cmd, 3, set.raw);
                        let slots = config::POINTS_PER_TRIANGLE;
                        mesh.draw_slots(cmd, self.pipeline.layout, &scene_gpu.material_sets, slots);
                    }
                }
            });
        }
        if let Some(r) = &self.refine {
            r.record(&self.ctx, cmd, scene_gpu, &self.set);
        }
    }

    /// Whether the points are refined where the camera looks (the voxels then follow it).
    pub fn refines(&self) -> bool {
        self.refine.is_some()
    }

    pub fn notes(&self) -> Vec<String> {
        let refined = if self.refine.is_some() { ", refined where the camera looks" } else { "" };
        vec![match self.source {
            PointSource::Load => {
                format!("points: {} sample points at {} per voxel area{refined}", self.count, self.density)
            }
            PointSource::Gpu => format!(
                "points: generated on the GPU at {} per voxel area over {} triangles (split to {} points at most){refined}",
                self.density,
                self.count,
                config::POINTS_PER_TRIANGLE
            ),
        }]
    }
}
