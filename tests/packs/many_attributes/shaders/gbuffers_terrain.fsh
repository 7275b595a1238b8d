#version 150 compatibility
in vec4 colour;
void main() {
    gl_FragData[0] = colour;
}
