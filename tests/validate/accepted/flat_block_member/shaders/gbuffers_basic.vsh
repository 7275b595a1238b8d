#version 330 compatibility
// Interpolation qualifiers on block members (GLSL 1.50); an integer member must be flat.
out VertexData {
    flat int id;
    vec2 uv;
    smooth vec4 color;
} vOut;
void main() {
    gl_Position = ftransform();
    vOut.id = int(gl_MultiTexCoord1.x);
    vOut.uv = gl_MultiTexCoord0.xy;
    vOut.color = gl_Color;
}
