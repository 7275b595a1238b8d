#version 120
// Three mistakes in one stage, in two functions and main: each is reported, not only the first.
uniform sampler2D colortex0;
varying vec2 uv;
float first(vec2 p) {
    vec3 wrong = p;
    return wrong.x;
}
float second(float x) {
    return x * undeclaredThing;
}
void main() {
    float a = first(uv) + second(uv.x);
    gl_FragData[0] = vec4(a) * texture2D(colortex0, uv) + missingCall(a);
}
