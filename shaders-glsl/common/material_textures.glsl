// Set 1: the drawn material's textures, bound per draw (`MeshBuffers::draw`).
#ifndef VCT_MATERIAL_TEXTURES_GLSL
#define VCT_MATERIAL_TEXTURES_GLSL

layout(set = 1, binding = 0) uniform sampler2D albedo_texture;
layout(set = 1, binding = 1) uniform sampler2D normal_texture;

#endif
