#version 120
void main() {
    gl_FragData[0] = vec4(0.2, 0.4, 0.8, 0.5);
}
