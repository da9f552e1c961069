// Surface shading shared by the forward fragment shader and the deferred compute shader
// (Freed 2018 §4.5, Algorithm 3): emission plus Cook-Torrance direct light (3x3 PCF shadow)
// plus indirect light by voxel cone tracing — the diffuse cone set (common/gather.glsl) and one
// specular cone along the reflection (as wide as the GGX lobe), either traced here or given
// (traced at a reduced resolution: shade/deferred.comp). Diffuse-cone occlusion gives
// ambient occlusion.
// The includer binds `shadow_map` (sampler2DArrayShadow: one layer, or a point light's six), `radiance_volume` (sampler3D), the moment
// `radiance_moment` and the directional chains' atlas `radiance_aniso` (sampled when the
// ANISOTROPIC specialization constant is set; a constant, so the isotropic variant carries no
// extra work).
#ifndef VCT_SHADING_GLSL
#define VCT_SHADING_GLSL
#include "frame.glsl"
#include "brdf.glsl"
#include "light.glsl"
#include "shadow.glsl"

layout(constant_id = 0) const bool ANISOTROPIC = false;
// An includer that knows no material reflects specularly defines this false (a specialization
// constant, scene::gpu::SceneGpu::specular), and the specular cone's code is left out.
#ifndef VCT_SPECULAR
#define VCT_SPECULAR true
#endif

#include "gather.glsl"

// The specular reflectance at normal incidence (dielectric: the material's; metal: its albedo).
vec3 specular_f0(Material m, vec3 albedo) {
    return mix(m.specular.rgb, albedo, m.albedo.a);
}

// The specular cone's full aperture for a material of `roughness`: as wide as the lobe the
// Cook-Torrance term reflects. GGX's D (alpha = roughness^2, common/brdf.glsl) falls to half its
// peak where tan(theta_h) = alpha sqrt(sqrt(2) - 1), and the reflected directions spread twice as
// far as the half vectors, so the cone's half angle is 2 theta_h.
float specular_aperture(float roughness) {
    float alpha = roughness * roughness;
    return max(4.0 * atan(alpha * sqrt(sqrt(2.0) - 1.0)), MIN_SPECULAR_APERTURE);
}

// The radiance the specular cone (along the reflection of the view direction `v` about `n`,
// `specular_aperture` wide) brings, before the Fresnel factor.
vec3 specular_cone(Material m, vec3 uvw, vec3 n, vec3 v, ConeParams p) {
    return trace_frame_cone(uvw, n, reflect(-v, n), tan(0.5 * specular_aperture(m.emissive.a)), p).rgb;
}

// The shading normal turned to the side facing the viewer (surfaces are two-sided).
vec3 facing_normal(vec3 n, vec3 world) {
    return dot(n, frame.camera_pos.xyz - world) < 0.0 ? -n : n;
}

// The texel size at `world` as a colour, after the thesis' Figure 5.7: green where texels are an
// even grid's, towards blue where they are finer (1.5 times: full blue) and towards red where
// they are coarser (4 times: full red). In a clipmap, the finest level holding the point, where
// its cones start: green in level 0, through to full red in the coarsest.
vec3 texel_size_colour(vec3 world) {
    float t = warp_on(frame.voxel_warp) ? log2(warp_local_slope(world_to_march(world), frame.voxel_warp, frame.voxel_warp_proj)) : 0.0;
    if (clip_on()) t = -2.0 * float(clip_level_of(world_to_grid(world))) / max(frame.clip.x - 1.0, 1.0);
    vec3 even = vec3(0.1, 0.8, 0.1);
    return t >= 0.0 ? mix(even, vec3(0.1, 0.2, 1.0), min(t / log2(1.5), 1.0)) : mix(even, vec3(1.0, 0.1, 0.1), min(-t / 2.0, 1.0));
}

// Radiance leaving `world` towards the camera (or the debug view chosen in frame.view), for
// material `m` with its textures already applied: `albedo` and shading normal `n`. `given`:
// the diffuse cones' gather (rgb light, a occlusion) was traced elsewhere (at a reduced
// resolution, then upsampled: shade/deferred.comp) and is `gathered_in`; `specular_given`: so
// was the specular cone's light (`specular_cone`), `specular_in`. `px`: the pixel shaded.
vec3 shade_surface_given(Material m, vec3 albedo, vec3 n, vec3 world, bool given, vec4 gathered_in,
                         bool specular_given, vec3 specular_in, ivec2 px) {
    float roughness = m.emissive.a, metallic = m.albedo.a;
    vec3 v = normalize(frame.camera_pos.xyz - world);
    n = facing_normal(n, world);

    vec3 direct = vec3(0.0);
    for (int j = 0; j < light_count(); j++) {
        vec3 l;
        vec3 irradiance = light_incident(j, world, n, l);
        if (dot(n, l) > 0.0 && max(irradiance.r, max(irradiance.g, irradiance.b)) > 0.0) {
            direct += irradiance * cook_torrance(n, v, l, albedo, m.specular.rgb, roughness, metallic) * shadow_factor(j, world, n);
        }
    }
    vec3 diffuse = vec3(0.0), specular = vec3(0.0);
    float occlusion = 0.0;
    if (frame.view.z > 0.5) {
        ConeParams p = frame_cone_params();
        vec3 uvw = world_to_march(world);
        vec4 gathered = given ? gathered_in : gather_diffuse(uvw, n, p, px);
        occlusion = gathered.a;
        // Outgoing diffuse = albedo/pi * integral(L cos) = albedo * sum(w_i L_i).
        diffuse = albedo * (1.0 - metallic) * gathered.rgb;
        vec3 f0 = specular_f0(m, albedo);
        if (VCT_SPECULAR && max(f0.r, max(f0.g, f0.b)) > 0.0) {
            vec3 c = specular_given ? specular_in : specular_cone(m, uvw, n, v, p);
            vec2 e = ggx_albedo(dot(n, v), roughness);
            specular = (e.x + f0 * e.y) * c;
        }
    }

    vec3 indirect = diffuse + specular;
    vec3 result;
    switch (uint(frame.view.x)) {
        case VIEW_DIRECT: result = m.emissive.rgb + direct; break;
        case VIEW_INDIRECT: result = indirect; break;
        case VIEW_DIFFUSE: result = diffuse; break;
        case VIEW_SPECULAR: result = specular; break;
        case VIEW_AO: result = vec3(1.0 - occlusion); break;
        case VIEW_TEXELS: result = texel_size_colour(world); break;
        default: result = m.emissive.rgb + direct + indirect; break;
    }
    return result;
}

vec3 shade_surface(Material m, vec3 albedo, vec3 n, vec3 world, ivec2 px) {
    return shade_surface_given(m, albedo, n, world, false, vec4(0.0), false, vec3(0.0), px);
}

#endif
