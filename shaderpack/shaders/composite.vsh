#version 330 compatibility
// Full-screen pass: one quad covering the screen.

out vec2 screenUv;

void main() {
    gl_Position = ftransform();
    screenUv = gl_MultiTexCoord0.xy;
}
