#version 120
// The light colour is declared for the fragment stage and never assigned.
varying vec3 lightColor;
varying vec4 color;
void main() {
    color = gl_Color;
    gl_Position = ftransform();
}
