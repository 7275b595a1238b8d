#version 430 compatibility
layout(std430, binding = 0) readonly buffer sharedData {
    vec3 tint;
    float strength;
} shared_;
uniform sampler2D gtexture;
in vec2 uv;
in vec4 color;
layout(location = 0) out vec4 outColor0;
void main() {
    outColor0 = texture(gtexture, uv) * color * shared_.strength;
}
