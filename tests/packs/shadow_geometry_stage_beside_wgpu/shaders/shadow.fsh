#version 150 compatibility
in vec4 shadowColor;
void main() {
    gl_FragData[0] = shadowColor;
}
