#version 150 compatibility
// The terrain as the game draws it; the geometry stage colours it.
out vec4 vertexColor;
void main() {
    gl_Position = ftransform();
    vertexColor = gl_Color;
}
