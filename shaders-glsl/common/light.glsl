// The scene's one light: direction to it and the irradiance it delivers to a point (before
// shadowing and n.l). Spot: intensity/d^2, falloff linear in angle from inner to outer; point:
// intensity/d^2. A point light's shadow map is a cube, one layer per face (render::frame).
#ifndef VCT_LIGHT_GLSL
#define VCT_LIGHT_GLSL
#include "frame.glsl"

// Returns irradiance on a plane facing the light; `l` gets the unit vector towards the light.
vec3 light_incident(vec3 p, out vec3 l) {
    if (uint(frame.light_pos.w) == LIGHT_DIRECTIONAL) {
        l = -frame.light_dir.xyz;
        return frame.light_color.rgb;
    }
    vec3 to_light = frame.light_pos.xyz - p;
    float d2 = max(dot(to_light, to_light), 1e-8);
    l = to_light * inversesqrt(d2);
    if (uint(frame.light_pos.w) == LIGHT_POINT) return frame.light_color.rgb / d2;
    float angle = acos(clamp(dot(-l, frame.light_dir.xyz), -1.0, 1.0));
    float inner = frame.light_cone.x, outer = frame.light_cone.y;
    float falloff = outer > inner ? clamp((outer - angle) / (outer - inner), 0.0, 1.0) : float(angle <= outer);
    return frame.light_color.rgb * falloff / d2;
}

// The shadow map's world-to-clip matrix for a point `p` and its layer: a point light's cube face
// along the major axis of the direction from the light (+x, -x, +y, -y, +z, -z), else the one map.
mat4 shadow_view_proj(vec3 p, out int layer) {
    layer = 0;
    if (uint(frame.light_pos.w) != LIGHT_POINT) return frame.light_view_proj;
    vec3 d = p - frame.light_pos.xyz, a = abs(d);
    int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    layer = 2 * axis + (d[axis] < 0.0 ? 1 : 0);
    return frame.light_faces[layer];
}

#endif
