#version 130
// `flat varying`: GLSL 1.30 refuses it, Iris writes it `flat out` at 3.30.
flat varying vec3 tint;
varying vec2 texcoord;
void main() {
    gl_Position = ftransform();
    texcoord = gl_MultiTexCoord0.xy;
    tint = vec3(0.5);
}
