#version 430 compatibility
// `coord` is never written by the vertex stage; only locals and parameters of that name are
// read, so the input is not statically used and the program links.
uniform sampler2D colortex0;
uniform float viewWidth;
uniform float viewHeight;
in vec2 uv;
in vec2 coord;
layout(location = 0) out vec4 outColor0;
vec4 fetch(vec2 coord) {
    return texture(colortex0, coord);
}
void main() {
    vec2 coord = gl_FragCoord.xy / vec2(viewWidth, viewHeight);
    {
        coord += uv * 0.0;
    }
    outColor0 = fetch(coord);
}
