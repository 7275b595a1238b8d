#version 120
// As mateuskreuch/minecraft-miniature-shader writes it: GLSL 1.20 has no round(), so the
// pack defines its own, for a float and a vec3.
uniform sampler2D colortex0;
varying vec2 uv;
float round(float x) {
    return floor(x + 0.5);
}
vec3 round(vec3 x) {
    return floor(x + 0.5);
}
void main() {
    vec3 colour = texture2D(colortex0, uv).rgb;
    gl_FragColor = vec4(round(colour * 8.0) / 8.0, round(0.4));
}
