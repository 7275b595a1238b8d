#version 150 compatibility
// Passes each triangle on unchanged: wgpu runs no geometry stage, so OpenGL alone draws the
// shadow map.
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
in vec4 vertexColor[3];
out vec4 shadowColor;
void main() {
    for (int i = 0; i < 3; i++) {
        gl_Position = gl_in[i].gl_Position;
        shadowColor = vertexColor[i];
        EmitVertex();
    }
    EndPrimitive();
}
