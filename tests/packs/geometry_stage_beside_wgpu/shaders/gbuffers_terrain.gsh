#version 150 compatibility
// Passes each triangle on with a colour only this stage writes: green where the triangle's
// vertices are, so a frame drawn without the geometry stage shows none.
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
in vec4 vertexColor[3];
out vec3 shade;
void main() {
    for (int i = 0; i < 3; i++) {
        gl_Position = gl_in[i].gl_Position;
        shade = vec3(0.0, 1.0, 0.0) * vertexColor[i].a;
        EmitVertex();
    }
    EndPrimitive();
}
