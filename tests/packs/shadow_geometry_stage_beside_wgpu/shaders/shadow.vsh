#version 150 compatibility
// The shadow pass as the game draws it; the geometry stage passes it on.
out vec4 vertexColor;
void main() {
    gl_Position = ftransform();
    vertexColor = gl_Color;
}
