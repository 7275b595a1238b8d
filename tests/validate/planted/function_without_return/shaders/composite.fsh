#version 120
varying vec2 uv;
float twice(float x) {
    x *= 2.0;
}
void main() {
    gl_FragData[0] = vec4(twice(uv.x));
}
