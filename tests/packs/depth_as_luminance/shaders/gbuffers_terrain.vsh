#version 120
// The terrain as the game draws it.
void main() {
    gl_Position = ftransform();
}
