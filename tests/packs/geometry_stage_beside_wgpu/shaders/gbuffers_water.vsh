#version 150 compatibility
// The water as the game draws it; wgpu can draw this program.
void main() {
    gl_Position = ftransform();
}
