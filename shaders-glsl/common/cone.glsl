// Voxel cone tracing (Freed 2018 §4.5.2, Listing 4.1): front-to-back accumulation of the
// pre-filtered radiance volume along a cone, sampling the mip level whose voxels match the
// cone's diameter. Heights are in voxels of level 0. One deviation from the listing: each step
// advances at least half a voxel, so narrow (specular) cones still reach past their start.
#ifndef VCT_CONE_GLSL
#define VCT_CONE_GLSL

struct ConeParams {
    int steps;         // maximum samples
    float bias;        // start offset along the surface normal (voxels)
    float start;       // initial cone height (voxels)
    float lod_offset;  // added to the sampled level
    float resolution;  // N
};

// Anisotropic sample (Crassin et al. 2011): the three directional volumes facing the cone,
// weighted by the squared direction components. The directional chains start at level 1;
// between levels 0 and 1 the isotropic level 0 is blended in.
vec4 sample_aniso(sampler3D iso, sampler3D px, sampler3D nx, sampler3D py, sampler3D ny, sampler3D pz, sampler3D nz,
                  vec3 pos, vec3 dir, float lod) {
    float l = max(lod - 1.0, 0.0);
    vec3 w = dir * dir;
    // Branches, not ?: selects, so only the three facing volumes are sampled.
    vec4 a;
    if (dir.x >= 0.0) a = w.x * textureLod(px, pos, l); else a = w.x * textureLod(nx, pos, l);
    if (dir.y >= 0.0) a += w.y * textureLod(py, pos, l); else a += w.y * textureLod(ny, pos, l);
    if (dir.z >= 0.0) a += w.z * textureLod(pz, pos, l); else a += w.z * textureLod(nz, pos, l);
    if (lod < 1.0) a = mix(textureLod(iso, pos, 0.0), a, lod);
    return a;
}

// Returns accumulated radiance (rgb, premultiplied) and opacity (a). With `aniso` the six
// directional volumes are sampled; otherwise only the isotropic `volume` (the thesis).
vec4 trace_cone_filtered(sampler3D volume, sampler3D px, sampler3D nx, sampler3D py, sampler3D ny, sampler3D pz,
                         sampler3D nz, bool aniso, vec3 uvw, vec3 normal, vec3 dir, float aperture, ConeParams p) {
    float scale = 1.0 / p.resolution;
    vec3 start = uvw + p.bias * normal * scale;
    float height = p.start;
    float tan_half = tan(aperture * 0.5);
    vec3 color = vec3(0.0);
    float alpha = 0.0;
    for (int i = 0; i < p.steps && alpha < 0.95; i++) {
        float radius = height * tan_half;
        float lod = log2(max(1.0, 2.0 * radius));
        vec3 pos = start + height * dir * scale;
        if (any(lessThan(pos, vec3(0.0))) || any(greaterThan(pos, vec3(1.0)))) break;
        float l = max(lod + p.lod_offset, 0.0);
        vec4 s;
        if (aniso) s = sample_aniso(volume, px, nx, py, ny, pz, nz, pos, dir, l);
        else s = textureLod(volume, pos, l);
        float a = 1.0 - alpha;
        color += s.rgb * a;
        alpha += a * s.a;
        height += max(radius, 0.5);
    }
    return vec4(color, alpha);
}

// The thesis' isotropic cone trace (Listing 4.1).
vec4 trace_cone(sampler3D volume, vec3 uvw, vec3 normal, vec3 dir, float aperture, ConeParams p) {
    return trace_cone_filtered(volume, volume, volume, volume, volume, volume, volume, false, uvw, normal, dir, aperture, p);
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
