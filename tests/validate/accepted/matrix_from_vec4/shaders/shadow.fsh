#version 330 compatibility
void main() {
    gl_FragData[0] = vec4(1.0);
}
