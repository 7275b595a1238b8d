#version 430 compatibility
// Buffer and uniform blocks at binding 0 beside loose uniforms and samplers (GLSL 4.30).
layout(std430, binding = 0) readonly buffer sharedData {
    vec3 tint;
    float strength;
} shared_;
layout(std140, binding = 0) uniform Extra {
    vec4 offset;
};
uniform sampler2D lightmap;
out vec2 uv;
out vec4 color;
void main() {
    gl_Position = ftransform() + offset * 0.0;
    uv = gl_MultiTexCoord0.xy;
    color = gl_Color * vec4(shared_.tint * shared_.strength, 1.0) * texture(lightmap, vec2(0.5));
}
