// Voxel cone tracing (Freed 2018 §4.5.2, Listing 4.1; Crassin et al. 2011 §4): front-to-back
// accumulation of the pre-filtered radiance volume along a cone. Distances are in voxels of
// level 0. Three choices are parameters, each measured in the study of docs/design/cones.md:
// - the sampled level: log2 of the cone diameter plus an offset (the level rule's and the
//   user's), and, with CONE_FLAG_SELF_CLAMP, no coarser than keeps the trilinear filter's
//   support off the receiving surface's own voxels;
// - the step: a fraction of the sampled level's texel (Listing 4.1 steps by the cone's radius,
//   half its diameter, with texels as wide as the cone: 0.5). Two samples a texel keep a wall one
//   texel thick opaque: trilinear filtering spreads its opacity over two texels, and fewer samples
//   of that spread let a cone through it (an emissive closed box then gathered 11% too little);
// - with CONE_FLAG_OPACITY_CORRECTION, each sample's opacity corrected for the step length
//   against the voxel size of its level (Crassin et al. 2011: a' = 1 - (1 - a)^(step/voxel)),
//   its radiance scaled alike (premultiplied). Measured, it loses more than it mends: trilinear
//   filtering makes a tent of an opaque one-texel wall, and corrected tents let cones through
//   walls (an emissive closed box gathered 16% too little); uncorrected, two samples a texel
//   count a texel's partial cover more than once (a small emitter lights the floor below it up
//   to twice too brightly). Off by default;
// - with CONE_FLAG_FACING, a sample's light is hidden by the share of it that leaves its surfaces
//   away from the cone: the radiance moment volume (from level 1) holds, per texel, the luminance-weighted sum of
//   the lit sides' normals and the luminance, and light that all leaves into one hemisphere
//   (moment length equal to the luminance) cannot reach a cone behind that hemisphere. This is
//   what keeps the lit outside of a thin wall from shining into the room through the
//   directional chains that see the wall edge-on (`facing_across`).
// A cone ends when 95% opaque or when it leaves the volume.
// A cone marches in the unwarped grid, where it is straight. In a warped grid (Freed 2018 §4.6)
// each sample is warped to its texture coordinates, and its level and step follow the local
// texel size: a texel there is 1/s of a grid voxel along each axis (s the warp's slope), and the
// cone's diameter is measured in texels of the geometric mean of the three.
#ifndef VCT_CONE_GLSL
#define VCT_CONE_GLSL
#include "config.h"
#include "warp.glsl"

struct ConeParams {
    int steps;         // maximum samples
    float bias;        // start offset along the surface normal (voxels)
    float start;       // initial distance along the cone (voxels)
    float lod_offset;  // added to log2(diameter)
    vec3 dims;         // voxels along each axis
    float max_level;   // the coarsest mip level
    float step;        // step length over the sampled level's texel size
    uint flags;        // CONE_FLAG_*
    float surface;     // how far the receiving surface's own voxels may reach above the start's
                       // plane (voxels): half a voxel for a point on the surface
    vec3 atlas;        // the directional chains' atlas (frame.glsl, aniso_atlas)
    float chain_base;  // the isotropic chain's mip that holds level 1 (0: a chain of its own)
    vec4 warp;         // the grid's warp (common/warp.glsl; w = 1: none)
    float normal_fine; // texels per grid voxel along the normal where the cone starts (at_start)
    int start_level;   // a clipmap's level whose texels the start offsets are in, at the least (a
                       // voxel's gather: its own level's; 0: the finest that holds the start)
    mat4 warp_proj;    // a perspective warp's grid fraction to texture fraction (common/warp.glsl)
};

// Level 0 at `pos`, trilinearly filtered (common/level0.glsl, or the includer's own).
vec4 level0_sample(sampler3D level0, vec3 pos);

// Anisotropic sample (Crassin et al. 2011): the three directional chains facing the cone, weighted
// by the squared direction components `w`; `chain` holds each axis's chain, stacked in the atlas
// as `atlas` says (render::radiance::AtlasLayout: axis, pitch and length over a chain's length).
// The chains start at level 1 (their mip 0). `face` holds, per axis, the share of that chain's
// light that can reach the cone (see `facing_across`).
// With CONE_FLAG_CHAIN_BOX each chain is read as boxes along its own axis and the chains' optical
// depths are added (a study variant, measured in docs/design/cones.md; not the default). A chain's
// texel holds the opacity of crossing it whole along its axis (gi/filter_aniso.comp composites
// along it), so read at the nearest texel along that axis and corrected for the step (accumulate)
// it counts once per texel crossed, at any sample phase, where trilinear filtering makes a tent of
// a one-texel wall that a corrected cone passes through. Across the axis it stays trilinear: a
// texel's opacity there is a lateral average of cover. And a cone crossing a wall aslant advances
// |d_a| of its step along each axis a, so each chain's depth, -ln(1 - alpha_a), counts by |d_a|:
// blended as opacities by d_a^2 (the default), a wall crossed at a grazing angle lets a tenth of
// the light through.

// Where chain `c` (of axis `a`) is read for a sample at `pos` of chain mip `l`: in its block of the
// atlas, and with `box` at the centre of its texel along `a` (of mip floor(l)).
vec3 chain_at(sampler3D tex, vec3 pos, int a, float c, float l, vec3 atlas, bool box) {
    int axis = int(atlas.x);
    if (box) {
        float n = float(textureSize(tex, int(max(l, 0.0)))[a]) / (a == axis ? atlas.z : 1.0);
        pos[a] = (floor(pos[a] * n) + 0.5) / n;
    }
    pos[axis] = (pos[axis] + c * atlas.y) / atlas.z;
    return pos;
}

vec4 sample_chains(sampler3D tex, vec3 pos, vec3 w, vec3 chain, float lod, vec3 face, vec3 atlas, uint flags) {
    float l = lod - 1.0;
    bool box = (flags & CONE_FLAG_CHAIN_BOX) != 0u;
    vec4 x = textureLod(tex, chain_at(tex, pos, 0, chain.x, l, atlas, box), l);
    vec4 yy = textureLod(tex, chain_at(tex, pos, 1, chain.y, l, atlas, box), l);
    vec4 z = textureLod(tex, chain_at(tex, pos, 2, chain.z, l, atlas, box), l);
    vec3 wf = w * face;
    vec4 s = vec4(wf.x * x.rgb + wf.y * yy.rgb + wf.z * z.rgb, w.x * x.a + w.y * yy.a + w.z * z.a);
    if (box && s.a > 1e-6) {
        // Optical depths by the advance along each axis (opaque: OPAQUE_DEPTH).
        vec3 a = vec3(x.a, yy.a, z.a);
        float tau = dot(sqrt(w), -log(max(1.0 - a, vec3(exp(-OPAQUE_DEPTH)))));
        float cover = 1.0 - exp(-tau);
        s = vec4(s.rgb * (cover / s.a), cover);
    }
    return s;
}

// The level whose trilinear filter stays off the receiving surface, for a sample `height`
// voxels above its plane, the surface's own voxels reaching `surface` voxels above it. A level-L
// texel is s = 2^L voxels wide; the surface's texels have their centres within s/2 + surface of
// the plane, and trilinear filtering reaches texel centres up to s away. So a sample sees none of
// its own surface while height >= 1.5 s + surface. Without this, a cone's first coarse samples
// are darkened by the very surface it leaves (opaque, and dark from behind), which makes
// ceilings dim (the furnace: a voxel's second bounce gathers 20% too little). A point on a
// surface has its voxels within half a voxel; a voxel's centre may lie
// half a voxel below its surface, with a second layer above it (a wall on a voxel boundary).
float self_clamp_level(float height, float surface) {
    // A fractional level blends the texels of the level above (twice as wide): they too must
    // stay clear, so the level is kept one below the widest clear texel.
    return log2(max((height - surface) / 1.5, 1.0)) - 1.0;
}

// A cone's start offsets are in texels: in a warped grid, in the texels where it starts, as
// deep as they reach along the normal (a cone leaving a wall whose texels are four grid voxels
// thick starts four times as far out, clear of them, as it does from a wall of even texels).
ConeParams at_start(ConeParams p, vec3 uvw, vec3 normal) {
    if (warp_on(p.warp)) {
        vec3 n = abs(normal);
        // A perspective texel is a slanted cell, far ones several times deeper than wide: how far
        // along the normal the point moves one texel on the axis it crosses fastest.
        vec3 across = warp_projective(p.warp) ? abs(warp_project_along(uvw, normal, p.dims, p.warp_proj)) : vec3(0.0);
        float deep = warp_projective(p.warp) ? 1.0 / max(max(across.x, across.y), max(across.z, 1e-6))
                                             : dot(n, 1.0 / warp_slope(uvw, p.warp)) / max(n.x + n.y + n.z, 1e-6);
        p.bias *= deep;
        p.start *= deep;
        p.normal_fine = 1.0 / deep;
    }
    return p;
}

// The state of a cone along its march.
struct March {
    vec3 color;
    float alpha;
    float dist;
};

// Where the cone's next sample lies (texture coordinates), its level and its step (grid
// voxels; false once it leaves the volume). `start` and the march are in the unwarped grid.
bool next_sample(March m, vec3 start, vec3 dir, float tan_half, float rise, ConeParams p, out vec3 pos,
                 out float level, out float step) {
    pos = start + m.dist * dir / p.dims;
    // Texels per grid voxel here (1 unwarped).
    float fine = warp_on(p.warp) ? warp_local_slope(pos, p.warp, p.warp_proj) : 1.0;
    float diameter = max(2.0 * m.dist * tan_half * fine, 1.0);
    float l = log2(diameter) + p.lod_offset;
    if ((p.flags & CONE_FLAG_SELF_CLAMP) != 0u) {
        l = min(l, self_clamp_level((p.bias + m.dist * rise) * p.normal_fine, p.surface));
    }
    // Past the coarsest level (a grid's shortest axis is one texel there) a texel no longer
    // grows with the cone: the cone samples that level, stepping by its texel.
    level = clamp(l, 0.0, p.max_level);
    step = p.step * exp2(level) / fine;
    // The cone has left the volume once its sample's trilinear filter no longer reaches inside:
    // half a texel of its level beyond the edge. Stopping at the edge itself would cut short the
    // filter of every texel on the boundary, and walls the grid is fitted to would lose a fifth
    // of their light.
    vec3 reach = 0.5 * exp2(level) / fine / p.dims;
    bool inside = all(greaterThan(pos, -reach)) && all(lessThan(pos, 1.0 + reach));
    if (warp_projective(p.warp)) {
        // The texels fill the frustum, not the grid's box: inside is among them (the frustum is
        // convex, so a cone that leaves it does not come back).
        pos = warp_project(pos, p.warp, p.warp_proj);
        reach = 0.5 * exp2(level) / p.dims;
        return all(greaterThan(pos, -reach)) && all(lessThan(pos, 1.0 + reach));
    }
    if (warp_on(p.warp)) pos = warp_forward(pos, p.warp);
    return inside;
}

// The radiance moment at a sample of `level`: the moment volume starts at level 1 (its mip 0;
// gi/moment.comp), and a sample finer than that reads level 1.
vec4 sample_moment(sampler3D moment, vec3 pos, float level) {
    return textureLod(moment, pos, max(level - 1.0, 0.0));
}

// The share of light with radiance moment `m` (xyz: sum of luminance times lit normal; w:
// luminance) that can leave towards a cone travelling along `dir`: light whose surfaces all face
// away (moment as long as the luminance) is hidden, a mixture in proportion.
float facing_share(vec3 m, float lum, vec3 dir) {
    if (lum <= 1e-8) return 1.0;
    float away = dot(m, dir) / lum;  // coherence times the cosine of facing away
    return 1.0 - clamp(away / LIT_SIDE_EDGE, 0.0, length(m) / lum);
}

// The isotropic volume's share (every direction the moment holds).
float facing(vec4 mo, vec3 dir) {
    return facing_share(mo.xyz, mo.w, dir);
}

// Each directional chain's share: a chain already keeps dark the light whose surfaces face away
// along its own axis (the filter's lit-side weighting); what it cannot tell apart is light facing
// across its axis, which it sees edge-on — the lit outside of a thin wall. So each chain's share
// comes from the moment's part across its axis (left whole, light that another surface in the same
// texel turns towards the cone would be hidden along with it).
vec3 facing_across(vec4 mo, vec3 dir) {
    return vec3(facing_share(vec3(0.0, mo.yz), mo.w, vec3(0.0, dir.yz)),
                facing_share(vec3(mo.x, 0.0, mo.z), mo.w, vec3(dir.x, 0.0, dir.z)),
                facing_share(vec3(mo.xy, 0.0), mo.w, vec3(dir.xy, 0.0)));
}

// Composites sample `s` (premultiplied) of a step `step` long at `level` behind what the cone
// has. With CONE_FLAG_OPACITY_CORRECTION (or CONE_FLAG_CHAIN_BOX, from level 1 up) its opacity
// stands for crossing a whole texel of its level and is corrected for the step's length
// (Crassin et al. 2011).
void accumulate(inout March m, vec4 s, float level, float step, uint flags) {
    bool correct = (flags & CONE_FLAG_OPACITY_CORRECTION) != 0u ||
                   ((flags & CONE_FLAG_CHAIN_BOX) != 0u && level >= 1.0);
    if (correct && s.a > 1e-6) {
        float a = 1.0 - pow(max(1.0 - s.a, 0.0), step / exp2(level));
        s = vec4(s.rgb * (a / s.a), a);
    }
    float a = 1.0 - m.alpha;
    m.color += s.rgb * a;
    m.alpha += a * s.a;
    m.dist += step;
}

// A cone stops once 95% opaque; the light behind its last 5% is of the kind it saw so far, not
// black (left black, every gather of a closed room comes out 5% dark).
vec4 finish(March m) {
    return m.alpha >= 0.95 ? vec4(m.color / m.alpha, 1.0) : vec4(m.color, m.alpha);
}

// The thesis' march through the isotropic volume: level 0 in `volume`, the levels above it in
// `chain` (CONE_FLAG_CHAIN_BOX concerns the directional chains only). Below level 1 level 0 is
// blended in; that phase is a loop of its own, so a CPU driver does not read level 0 at every
// step (it flattens a branch inside a loop into running both sides).
vec4 march_iso(sampler3D volume, sampler3D chain, sampler3D moment, vec3 uvw, vec3 normal, vec3 dir, float tan_half,
               ConeParams p) {
    bool face = (p.flags & CONE_FLAG_FACING) != 0u;
    vec3 start = uvw + p.bias * normal / p.dims;
    float rise = dot(dir, normal);
    March m = March(vec3(0.0), 0.0, p.start);
    vec3 pos;
    float level, step;
    int i = 0;
    bool inside = true;
    for (; i < p.steps && m.alpha < 0.95; i++) {
        inside = next_sample(m, start, dir, tan_half, rise, p, pos, level, step);
        if (!inside || level >= 1.0) break;
        vec4 s = mix(level0_sample(volume, pos), textureLod(chain, pos, p.chain_base), level);
        if (face) s.rgb *= facing(sample_moment(moment, pos, level), dir);
        accumulate(m, s, level, step, p.flags & ~CONE_FLAG_CHAIN_BOX);
    }
    for (; inside && i < p.steps && m.alpha < 0.95; i++) {
        if (!next_sample(m, start, dir, tan_half, rise, p, pos, level, step)) break;
        vec4 s = textureLod(chain, pos, level - 1.0 + p.chain_base);
        if (face) s.rgb *= facing(sample_moment(moment, pos, level), dir);
        accumulate(m, s, level, step, p.flags & ~CONE_FLAG_CHAIN_BOX);
    }
    return finish(m);
}

// The anisotropic march through the directional chains of `atlas`. Below level 1 the isotropic
// level 0 is blended in; that phase is a loop of its own, so a CPU driver does not read level 0
// at every step (it flattens a branch inside a loop into running both sides).
vec4 march_aniso(sampler3D volume, sampler3D moment, sampler3D atlas, vec3 uvw, vec3 normal, vec3 dir, float tan_half,
                 ConeParams p) {
    bool face = (p.flags & CONE_FLAG_FACING) != 0u;
    vec3 start = uvw + p.bias * normal / p.dims;
    float rise = dot(dir, normal);
    vec3 w = dir * dir;
    // Chain of axis a: 2a for a cone travelling along +a, 2a + 1 along -a.
    vec3 chain = vec3(0.0, 2.0, 4.0) + vec3(lessThan(dir, vec3(0.0)));
    March m = March(vec3(0.0), 0.0, p.start);
    vec3 pos;
    float level, step;
    int i = 0;
    bool inside = true;
    for (; i < p.steps && m.alpha < 0.95; i++) {
        inside = next_sample(m, start, dir, tan_half, rise, p, pos, level, step);
        if (!inside || level >= 1.0) break;
        vec4 mo = face ? sample_moment(moment, pos, level) : vec4(0.0);
        vec4 iso = level0_sample(volume, pos);
        if (face) iso.rgb *= facing(mo, dir);
        vec4 s = mix(iso, sample_chains(atlas, pos, w, chain, 1.0, face ? facing_across(mo, dir) : vec3(1.0), p.atlas, p.flags), level);
        accumulate(m, s, level, step, p.flags);
    }
    for (; inside && i < p.steps && m.alpha < 0.95; i++) {
        if (!next_sample(m, start, dir, tan_half, rise, p, pos, level, step)) break;
        vec3 share = face ? facing_across(sample_moment(moment, pos, level), dir) : vec3(1.0);
        accumulate(m, sample_chains(atlas, pos, w, chain, level, share, p.atlas, p.flags), level, step, p.flags);
    }
    return finish(m);
}

#ifdef VCT_FRAME_GLSL
// A clipmap's cone (voxel::clipmap; Wicked Engine's VXGI): the cone marches in grid coordinates
// (voxels of level 0), and each sample reads the finest level that holds it with its filter's
// half texel to spare, at the mip that matches its footprint in that level's texels. So near the
// camera a narrow cone reads fine voxels, and as it widens or leaves a level it moves out to
// coarser ones. Within the blend band of a level's border (CLIP_BLEND_BAND of its side) the
// sample is blended linearly into the next level's, which it reaches fully at the border, so
// the doubling of the voxel there shows no seam. A sample is clamped inside its level's slab of
// the stack along z (half a texel of the mips it filters), so the filter never reads a
// neighbouring level.

// Where in level k a sample at grid point `g` of a cone `diameter` voxels of level 0 wide,
// `height` voxels of level 0 above its surface's plane, reads: texture coordinates `pos` and mip
// `level` (of level k's texels). Returns how far the filter's support lies inside the level's
// box from its closed faces (voxels of level 0; negative: it reaches out; clip_inside), and in
// `reach` from all its faces; `half_texel` is the filter's half texel.
float clip_place(vec3 g, float diameter, float height, int k, ConeParams p, out vec3 pos, out float level,
                 out float half_texel, out float reach) {
    float s = frame.clip_levels[k].w;
    float l = log2(max(diameter / s, 1.0)) + p.lod_offset;
    if ((p.flags & CONE_FLAG_SELF_CLAMP) != 0u) l = min(l, self_clamp_level(height / s, p.surface));
    level = clamp(l, 0.0, p.max_level);
    half_texel = 0.5 * exp2(level) * s;
    vec3 t = clip_texel(g, k);
    float n = frame.clip.y, slab = float(k) * n;
    // Below level 1 level 0 is blended with level 1, whose texels are two wide.
    float h = 0.5 * exp2(max(ceil(level), 1.0));
    t.z = clamp(t.z, slab + h, slab + n - h);
    pos = t / frame.voxel_dims.xyz;
    reach = clip_inside(g, k, false) - half_texel;
    return clip_inside(g, k, true) - half_texel;
}

// One sample of the volume at `pos` and `level`: below level 1 level 0 blended with level 1, as
// march_iso and march_aniso read it.
vec4 clip_read(sampler3D volume, sampler3D chain, sampler3D moment, sampler3D atlas, bool aniso, vec3 pos, float level,
               vec3 dir, vec3 w, vec3 chains, ConeParams p) {
    bool face = (p.flags & CONE_FLAG_FACING) != 0u;
    vec4 mo = face ? sample_moment(moment, pos, level) : vec4(0.0);
    float upper_level = max(level, 1.0);
    vec4 upper;
    if (aniso) {
        upper = sample_chains(atlas, pos, w, chains, upper_level, face ? facing_across(mo, dir) : vec3(1.0), p.atlas, p.flags);
    } else {
        upper = textureLod(chain, pos, upper_level - 1.0 + p.chain_base);
        if (face) upper.rgb *= facing(mo, dir);
    }
    if (level >= 1.0) return upper;
    vec4 iso = level0_sample(volume, pos);
    if (face) iso.rgb *= facing(mo, dir);
    return mix(iso, upper, level);
}

vec4 march_clip(sampler3D volume, sampler3D chain, sampler3D moment, sampler3D atlas, bool aniso, vec3 uvw,
                vec3 normal, vec3 dir, float tan_half, ConeParams p) {
    int levels = clip_count();
    vec3 g0 = uvw * frame.clip.y;
    // The start offsets are in texels of the finest level where the cone starts (at_start), or
    // of the level the start's own voxel is in, if coarser: a coarse voxel's centre may lie half
    // of its texel from its surface, and a cone leaving it by a finer level's texels would start
    // behind its own wall (its samples may then still read finer levels: the start is clear of
    // the surface there too).
    float s0 = frame.clip_levels[max(clip_level_of(g0), p.start_level)].w;
    float bias = p.bias * s0;
    vec3 start = g0 + bias * normal;
    float rise = dot(dir, normal);
    vec3 w = dir * dir;
    vec3 chains = vec3(0.0, 2.0, 4.0) + vec3(lessThan(dir, vec3(0.0)));
    March m = March(vec3(0.0), 0.0, p.start * s0);
    for (int i = 0; i < p.steps && m.alpha < 0.95; i++) {
        vec3 g = start + m.dist * dir;
        float diameter = 2.0 * m.dist * tan_half, height = bias + m.dist * rise;
        vec3 pos;
        float level, half_texel, reach;
        int k = 0;
        float room = clip_place(g, diameter, height, 0, p, pos, level, half_texel, reach);
        while (room < 0.0 && k + 1 < levels)
            room = clip_place(g, diameter, height, ++k, p, pos, level, half_texel, reach);
        // Left the coarsest level, or passed an open face (the scene's end): its filter no
        // longer reaches inside (as next_sample).
        if (reach <= -2.0 * half_texel) break;
        float s = frame.clip_levels[k].w;
        vec4 sample_k = clip_read(volume, chain, moment, atlas, aniso, pos, level, dir, w, chains, p);
        float band = frame.clip.z * frame.clip.y * s;
        if (k + 1 < levels && room < band) {
            vec3 pos2;
            float level2, half2, reach2;
            clip_place(g, diameter, height, k + 1, p, pos2, level2, half2, reach2);
            vec4 outer = clip_read(volume, chain, moment, atlas, aniso, pos2, level2, dir, w, chains, p);
            sample_k = mix(sample_k, outer, 1.0 - clamp(room / band, 0.0, 1.0));
        }
        // The step and the opacity correction in level k's texels (exp2(level) * s voxels of
        // level 0).
        accumulate(m, sample_k, level + log2(s), p.step * exp2(level) * s,
                   aniso ? p.flags : p.flags & ~CONE_FLAG_CHAIN_BOX);
    }
    return finish(m);
}
#endif

// Returns accumulated radiance (rgb, premultiplied) and opacity (a). With `aniso` the
// directional chains of `atlas` are sampled above level 0; otherwise the isotropic `chain` (the
// thesis). `volume` holds level 0. `tan_half`: tangent of the cone's half aperture.
vec4 trace_cone_filtered(sampler3D volume, sampler3D chain, sampler3D moment, sampler3D atlas, bool aniso, vec3 uvw,
                         vec3 normal, vec3 dir, float tan_half, ConeParams p) {
#ifdef VCT_FRAME_GLSL
    if (clip_on()) return march_clip(volume, chain, moment, atlas, aniso, uvw, normal, dir, tan_half, p);
#endif
    if (aniso) return march_aniso(volume, moment, atlas, uvw, normal, dir, tan_half, at_start(p, uvw, normal));
    return march_iso(volume, chain, moment, uvw, normal, dir, tan_half, at_start(p, uvw, normal));
}

// The thesis' isotropic cone trace (Listing 4.1) through one texture with the whole mip chain
// (`p.chain_base` 1).
vec4 trace_cone(sampler3D volume, vec3 uvw, vec3 normal, vec3 dir, float tan_half, ConeParams p) {
    return trace_cone_filtered(volume, volume, volume, volume, false, uvw, normal, dir, tan_half, p);
}

// An orthonormal tangent frame around n (Frisvad 2012, revised by Duff et al. 2017).
void tangent_frame(vec3 n, out vec3 t, out vec3 b) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

#endif
