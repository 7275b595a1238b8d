#version 120
uniform sampler2D colortex0;
varying vec2 uv;
void main() {
    vec3 color = texture2D(colortex0, uv).rgb;
    // cross() takes vec3s alone (naga says these arguments are invalid, not the function unknown).
    color += cross(uv, uv).x;
    gl_FragColor = vec4(color, 1.0);
}
