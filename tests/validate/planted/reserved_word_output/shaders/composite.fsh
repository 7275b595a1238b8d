#version 120
varying vec2 uv;
void main() {
    vec4 output = vec4(uv, 0.0, 1.0);
    gl_FragData[0] = output;
}
