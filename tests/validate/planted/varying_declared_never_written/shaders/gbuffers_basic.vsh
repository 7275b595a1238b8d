#version 130
// The colour is declared for the fragment stage and never assigned.
varying vec4 color;
void main() {
    gl_Position = ftransform();
}
