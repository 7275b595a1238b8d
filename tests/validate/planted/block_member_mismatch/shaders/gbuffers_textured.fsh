#version 330 compatibility
// The block has a member the vertex stage's `Surface` lacks: the blocks do not match.
in Surface {
    vec2 uv;
    vec3 normal;
    vec4 tint;
} fs;
layout(location = 0) out vec4 outColor0;
void main() {
    outColor0 = fs.tint * vec4(fs.normal * 0.5 + 0.5, fs.uv.x);
}
