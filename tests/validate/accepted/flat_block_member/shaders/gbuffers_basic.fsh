#version 330 compatibility
// Interpolation qualifiers on block members (GLSL 1.50); an integer member must be flat.
in VertexData {
    flat int id;
    vec2 uv;
    smooth vec4 color;
} vIn;
layout(location = 0) out vec4 outColor0;
void main() {
    outColor0 = vIn.color * vec4(vIn.uv, float(vIn.id), 1.0);
}
