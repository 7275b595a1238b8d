#version 120
varying vec2 uv;
uniform float viewWidth;
void main() {
    const float pixel = 1.0 / viewWidth;
    gl_FragData[0] = vec4(uv * pixel, 0.0, 1.0);
}
