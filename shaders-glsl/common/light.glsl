// The scene's lights (frame.lights): direction to light `j` and the irradiance it delivers to a
// point (before shadowing and n.l). Spot: intensity/d^2, falloff linear in angle from inner to
// outer; point: intensity/d^2; directional: its irradiance; area (an emissive quad, scene::area):
// the polygon's exact irradiance in vector form. Each light's shadow map is one layer of the
// layered shadow map, a point or area light's six, a cube (render::frame).
#ifndef VCT_LIGHT_GLSL
#define VCT_LIGHT_GLSL
#include "frame.glsl"

// An includer that knows no light is an area light defines this false (a specialization
// constant, scene::gpu::SceneGpu::area_lights): inlined into a loop over the lights, the
// polygon's code, though never run for a spot, keeps spot-lit injection at 1.7-2x the time it
// takes without, and the deferred shading of every pixel at 1.25x (docs/design/injection.md).
#ifndef VCT_AREA_LIGHTS
#define VCT_AREA_LIGHTS true
#endif

int light_count() {
    return int(frame.light_count.x);
}

// One edge's term of Arvo's sum (below), for corners `a`, `b` seen from the receiving point.
vec3 arvo_edge(vec3 a, vec3 b) {
    a = normalize(a);
    b = normalize(b);
    vec3 x = cross(a, b);
    float s = length(x);
    return s > 1e-7 ? x / s * atan(s, dot(a, b)) : vec3(0.0);
}

// An area light's irradiance at `p` on a plane of normal `n` (zero: no plane) as a vector:
// returned length times dot(n, l) is the irradiance. Lambert's formula for a polygon in Arvo's
// (1995) vector form: with the corners q_i seen from p, F = 1/2 sum theta_i normalize(q_i x q_i+1)
// (theta_i the angle between q_i and q_i+1), and a plane facing the polygon receives
// L |F . n| when the whole polygon lies above it; so the polygon is first clipped to n's
// horizon (Sutherland-Hodgman against one plane), edge by edge as the sum goes: an edge wholly
// above counts whole, one that crosses counts its part above, and the clipped polygon's closing
// edge runs along the horizon from where the outline leaves to where it comes back. Light leaves
// the side `direction` points to only. The clipped corners are not stored: a local array indexed
// in a loop makes lavapipe's injection of every light, spots included, 7x slower (1085 against
// 158 ms for the Cornell spot at 32³, docs/design/injection.md).
vec3 area_incident(LightData li, vec3 p, vec3 n, out vec3 l) {
    vec3 c = li.position.xyz - p;
    l = c / max(length(c), 1e-8);
    if (dot(c, li.direction.xyz) >= 0.0) return vec3(0.0);
    vec3 u = li.half_u.xyz, v = li.half_v.xyz;
    bool clip = dot(n, n) > 0.0;
    // Corners counter-clockwise about the light's normal (u x v): (-u -v), (+u -v), (+u +v), (-u +v).
    vec3 a = c - u - v, leave = vec3(0.0), enter = vec3(0.0), f = vec3(0.0);
    float da = clip ? dot(a, n) : 1.0;
    bool cut = false;
    for (int i = 1; i <= 4; i++) {
        int k = i & 3;
        vec3 b = c + u * (k == 1 || k == 2 ? 1.0 : -1.0) + v * (k >= 2 ? 1.0 : -1.0);
        float db = clip ? dot(b, n) : 1.0;
        vec3 x = a + (b - a) * (da / (da - db));
        if (da >= 0.0 && db >= 0.0) {
            f += arvo_edge(a, b);
        } else if (da >= 0.0) {
            f += arvo_edge(a, x);
            leave = x;
            cut = true;
        } else if (db >= 0.0) {
            f += arvo_edge(x, b);
            enter = x;
        }
        a = b;
        da = db;
    }
    if (cut) f += arvo_edge(leave, enter);
    // Corners counter-clockwise about a normal facing p sum to a vector pointing away from them.
    f *= -0.5;
    float len = length(f);
    if (len <= 0.0) return vec3(0.0);
    l = f / len;
    return li.color.rgb * len;
}

// Returns irradiance on a plane facing light `j` (an area light's: on the plane of normal `n`,
// zero for none, see area_incident); `l` gets the unit vector towards the light.
vec3 light_incident(int j, vec3 p, vec3 n, out vec3 l) {
    LightData li = frame.lights[j];
    if (VCT_AREA_LIGHTS && uint(li.position.w) == LIGHT_AREA) return area_incident(li, p, n, l);
    if (uint(li.position.w) == LIGHT_DIRECTIONAL) {
        l = -li.direction.xyz;
        return li.color.rgb;
    }
    vec3 to_light = li.position.xyz - p;
    float d2 = max(dot(to_light, to_light), 1e-8);
    l = to_light * inversesqrt(d2);
    if (uint(li.position.w) == LIGHT_POINT) return li.color.rgb / d2;
    float angle = acos(clamp(dot(-l, li.direction.xyz), -1.0, 1.0));
    float inner = li.cone.x, outer = li.cone.y;
    float falloff = outer > inner ? clamp((outer - angle) / (outer - inner), 0.0, 1.0) : float(angle <= outer);
    return li.color.rgb * falloff / d2;
}

// The world-to-clip matrix of light `j`'s shadow map for a point `p`, and its layer: a point or
// area light's cube face along the major axis of the direction from the light (+x, -x, +y, -y, +z,
// -z), else the light's one layer.
mat4 shadow_view_proj(int j, vec3 p, out int layer) {
    LightData li = frame.lights[j];
    layer = int(li.cone.w);
    if (uint(li.position.w) == LIGHT_POINT || uint(li.position.w) == LIGHT_AREA) {
        vec3 d = p - li.position.xyz, a = abs(d);
        int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
        layer += 2 * axis + (d[axis] < 0.0 ? 1 : 0);
    }
    return frame.light_layers[layer];
}

#endif
