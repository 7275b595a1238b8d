#version 330 compatibility
// The End's full-screen pass (see composite.fsh here).

out vec2 screenUv;

void main() {
    gl_Position = ftransform();
    screenUv = gl_MultiTexCoord0.xy;
}
