#version 120
// The vertex stage writes two components of a vec3 varying, and the fragment stage reads
// those two alone (as an argument, a swizzle and an element), which every driver links.
varying vec3 texcoord;
void main() {
    gl_Position = ftransform();
    texcoord.st = gl_MultiTexCoord0.st;
}
