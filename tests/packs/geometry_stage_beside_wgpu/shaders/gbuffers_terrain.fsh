#version 150 compatibility
in vec3 shade;
void main() {
    gl_FragData[0] = vec4(shade, 1.0);
}
