#version 120
// A bloom pass's tile: the left tile reads colortex1 through its mipmaps inside an `if` that
// splits the 2x2 quads of columns 100 and 101, where the level it picks is undefined. The
// lookup of colortex0 (no mipmaps) under the `if` splitting rows 50 and 51 reads alike at
// every level, and the `if` every fragment takes leaves the quads whole. Two tiles drawn by
// one function meet between columns 200 and 201: each fragment of those quads runs the same
// lookup once, but in another call, so the level is undefined there too.
const bool colortex1MipmapEnabled = true;
uniform sampler2D colortex0;
uniform sampler2D colortex1;
varying vec2 texcoord;
vec3 tile(vec2 offset, float left, float right) {
    vec3 color = vec3(0.0);
    if (gl_FragCoord.x >= left && gl_FragCoord.x < right) {
        color = texture2D(colortex1, texcoord * 4.0 + offset).rgb;
    }
    return color;
}
void main() {
    vec3 color = tile(vec2(0.25), 150.0, 201.0) + tile(vec2(0.5), 201.0, 300.0);
    if (gl_FragCoord.x < 101.0) {
        color = texture2D(colortex1, texcoord * 2.0).rgb;
    }
    if (gl_FragCoord.y < 51.0) {
        color += texture2D(colortex0, texcoord).rgb;
    }
    if (gl_FragCoord.x >= 0.0) {
        color *= texture2D(colortex1, texcoord).a;
    }
/* DRAWBUFFERS:2 */
    gl_FragData[0] = vec4(color, 1.0);
}
