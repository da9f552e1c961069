// The scene's lights (frame.lights): direction to light `j` and the irradiance it delivers to a
// point (before shadowing and n.l). Spot: intensity/d^2, falloff linear in angle from inner to
// outer; point: intensity/d^2; directional: its irradiance. Each light's shadow map is one layer
// of the layered shadow map, a point light's six, a cube (render::frame).
#ifndef VCT_LIGHT_GLSL
#define VCT_LIGHT_GLSL
#include "frame.glsl"

int light_count() {
    return int(frame.light_count.x);
}

// Returns irradiance on a plane facing light `j`; `l` gets the unit vector towards the light.
vec3 light_incident(int j, vec3 p, out vec3 l) {
    LightData li = frame.lights[j];
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

// The world-to-clip matrix of light `j`'s shadow map for a point `p`, and its layer: a point
// light's cube face along the major axis of the direction from the light (+x, -x, +y, -y, +z,
// -z), else the light's one layer.
mat4 shadow_view_proj(int j, vec3 p, out int layer) {
    LightData li = frame.lights[j];
    layer = int(li.cone.w);
    if (uint(li.position.w) == LIGHT_POINT) {
        vec3 d = p - li.position.xyz, a = abs(d);
        int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
        layer += 2 * axis + (d[axis] < 0.0 ? 1 : 0);
    }
    return frame.light_layers[layer];
}

#endif
