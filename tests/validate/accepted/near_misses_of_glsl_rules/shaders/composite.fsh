#version 120
varying vec2 uv;
uniform sampler2DShadow shadowtex0;
uniform float viewWidth;
// A return on one path only, a parameter and a local named like an input, a name close to a reserved word.
float scale(float x) { if (x > 0.0) return x; }
vec2 moved(vec2 uv) { uv *= 2.0; return uv; }
void main() {
    vec2 at = uv;
    at.x += 1.0 / viewWidth;
    const float k = 2.0;
    float output_ = shadow2D(shadowtex0, vec3(moved(at), 0.5)).r;
    gl_FragData[0] = vec4(output_ * k * scale(at.y));
}
