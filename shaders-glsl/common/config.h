// One source for the constants shared by Rust (build.rs turns each #define into a Rust const
// in `vct::config`) and GLSL (every shader includes this file). Integers only as plain
// decimal literals; floats with a decimal point.
#ifndef VCT_CONFIG_H
#define VCT_CONFIG_H

// Compute workgroup sizes (local_size_x; 3D kernels use N x N x N). WORKGROUP_2D a multiple of 4
// (shade/deferred.comp walks its workgroups in tiles of 4 x 2).
#define WORKGROUP_1D 64
#define WORKGROUP_2D 8
#define WORKGROUP_3D 4

// Materials: each material's textures are bound per draw (set 1); a flag says whether the
// material has the texture (absent ones are bound to a 1x1 white texel).
#define NO_TEXTURE 0
#define HAS_TEXTURE 1

// Lights: kinds as stored in LightGpu.kind_pad.x.
#define LIGHT_SPOT 0
#define LIGHT_DIRECTIONAL 1
#define LIGHT_POINT 2
#define LIGHT_AREA 3
// Lights per scene, each with its own shadow map (a point light's six cube faces, the others one
// layer each) in one layered shadow map.
#define MAX_LIGHTS 8
#define MAX_SHADOW_LAYERS 48


// Shadow filtering: PCF kernel radius in texels ((2r+1)^2 taps).
#define PCF_RADIUS 1
// Normal offset of the shadow lookup, in shadow texels at the receiver.
#define SHADOW_NORMAL_OFFSET 1.0
// Radiance injection looks for the lit voxel up to this many voxels before the shadow-map point
// (towards the light): the slope-scaled depth bias pushes grazing points behind their surface.
#define INJECT_SEARCH_VOXELS 3
// The point voxelizer generating its points on the GPU (voxel::points): vertex slots per
// triangle, each slot one point; triangles needing more are split when the scene loads.
#define POINTS_PER_TRIANGLE 8
// Floats per scene vertex (scene::Vertex: position, normal, UV, tangent), read as storage.
#define VERTEX_FLOATS 12
// Injection reads this many shadow-map texels per voxel width at the farthest lit point (every
// k-th texel of a finer map), so its cost follows the grid, not the map (render::inject).
// Measured (docs/design/injection.md): voxels of walls the light grazes are hit by
// few texels, so fewer than 8 changed Sponza's image (FLIP 0.025 at 4 against every texel);
// 8 changed neither test scene and only strides maps finer than 16 texels a voxel.
#define INJECT_TEXELS_PER_VOXEL 8.0

// Voxelization.
#define CAS_MAX_ITERATIONS 1024
// Tessellation path: keep every level >= 1, so a triangle inside one voxel still writes it.
#define VOXEL_FLAG_MIN_LEVEL 1
// Rasterized path: write every voxel layer the triangle's plane spans over the pixel.
#define VOXEL_FLAG_DEPTH_SPAN 2
// Rasterized path: conservative coverage without the extension (Hasselgren et al. 2005): the
// geometry shader moves each edge out by half a pixel diagonal, the fragment shader discards
// pixels outside the triangle's bounding box (and tests every voxel exactly).
#define VOXEL_FLAG_CONSERVATIVE 4
// Tessellation path: each evaluation point also tests the 26 voxels around its own against
// the triangle (exact triangle/box test) and fills those the triangle meets that nobody wrote.
#define VOXEL_FLAG_NEIGHBOURS 8

// Sparse storage (voxel::bricks, common/bricks.glsl): bricks of BRICK_SIZE³ voxels. The
// per-voxel textures are read texel by texel (never filtered), so a brick needs no apron and its
// size only trades the page table (4 bytes a brick) against the empty voxels of occupied
// bricks. Measured (docs/design/storage.md): 2³ bricks hold Sponza's 256-voxel
// grid in 19% of its texels and the Cornell box's 256³ in 5%; 4³ bricks need 38% and 10%, 8³
// 61% and 19%; with the table, 2³ costs the fewest bytes in both. At least 2: a level-1
// parent's eight children then share one brick (gi/filter_aniso.comp reads its page once).
#define BRICK_SIZE 2
#define BRICK_SHIFT 1
// Page-table entries that are no slot: being claimed, and refused (the pool is full).
#define BRICK_LOCKED 0xFFFFFFFFu
#define BRICK_REFUSED 0xFFFFFFFEu
#define BRICK_CLAIM_ITERATIONS 1024

// `--res auto` without a target (bench::auto): voxels a metre along the scene's longest axis.
// 12.5 cm voxels: the Cornell box (5.5 m) gets 64, where its FLIP against the path tracer is
// already what 256³ gives (docs/report/README.md); Sponza (34.8 m) the largest, 256.
#define AUTO_VOXELS_PER_METRE 8.0

// Global illumination (Freed 2018 §4.3-4.5).
// Diffuse cones: the largest cone set (scene::cones), each cone a direction in the surface's
// tangent frame, a weight and an aperture.
#define MAX_CONES 32
// Cone-tracing options (FrameUniforms.cone_model.z, a bit set).
// Crassin et al. 2011: a sample's opacity stands for one voxel of its level; a step of another
// length corrects it, alpha' = 1 - (1 - alpha)^(step / voxel).
#define CONE_FLAG_OPACITY_CORRECTION 1
// Keep the sampled level's filter off the receiving surface (common/cone.glsl).
#define CONE_FLAG_SELF_CLAMP 2
// Hide light that leaves its surface away from the cone (the radiance moment volume).
#define CONE_FLAG_FACING 4
// Each directional chain read as boxes along its own axis (nearest texel along it, trilinear
// across it), the chains' optical depths added by the cone's advance along each axis, and the
// opacity corrected for the step (common/cone.glsl, sample_chains).
#define CONE_FLAG_CHAIN_BOX 8
// Turn the surfaces' cone set about the normal by an angle of the pixel (common/gather.glsl,
// cone_turn).
#define CONE_FLAG_TURN 16
// The optical depth of an opaque texel: an opacity stored in fp16 is at most 1 - 2^-11 short of
// 1 (its step below 1), so ln 2048; a one-texel wall lets through what fp16 cannot tell from 0.
#define OPAQUE_DEPTH 7.624619
// Soft edge of "facing away" (a dot product of unit vectors): light whose surface normal is
// within this of perpendicular to the view counts in part.
#define LIT_SIDE_EDGE 0.25
// Narrowest specular cone (full aperture, radians): as wide as the GGX lobe (common/shading.glsl,
// specular_aperture), never below this.
#define MIN_SPECULAR_APERTURE 0.02
// Samples of the GGX lobe that weigh the specular cone's light (common/brdf.glsl, ggx_albedo).
#define SPECULAR_ALBEDO_SAMPLES 64
// Debug views (FrameUniforms.view.x).
// The viewer's on-screen overlay (post/overlay.comp): a block of text cells, each an 8x8 glyph
// times the overlay's scale, this far from the window's corner (pixels).
#define OVERLAY_COLUMNS 100
#define OVERLAY_ROWS 40
#define OVERLAY_MARGIN 6

#define VIEW_FULL 0
#define VIEW_DIRECT 1
#define VIEW_INDIRECT 2
#define VIEW_DIFFUSE 3
#define VIEW_SPECULAR 4
#define VIEW_AO 5
#define VIEW_VOXELS 6
#define VIEW_RADIANCE 7
#define VIEW_TEXELS 8

// The specialization constant WARPED (common/warp.glsl) of every pipeline: whether the grid is
// warped (gpu::pipeline::Stage::warped). Above every other constant id a shader declares.
#define WARP_CONSTANT_ID 16
// The specialization constant CLIPPED (common/frame.glsl): whether the volume is a clipmap's stack
// of levels (voxel::clipmap; gpu::pipeline::GridSpec).
#define CLIP_CONSTANT_ID 17

// Most levels of a clipmap (voxel::clipmap): the stack's z extent is levels * res <= 4096, the
// occupied list's 12 bits of z (common/occupied.glsl).
#define MAX_CLIP_LEVELS 8
// A cone sample within this share of a clipmap level's side of its border (after its own
// filter's half texel) blends linearly into the next level, so the switch of voxel size shows no
// seam (common/cone.glsl, march_clip). An eighth of the side: at N = 64, 8 texels of the level,
// 4 of the next.
#define CLIP_BLEND_BAND 0.125

#endif
