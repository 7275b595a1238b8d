#version 120
// Depth read through a sampler2D, all its channels: OptiFine's compatibility profile reads a
// depth texture as luminance, (d, d, d, 1). Green and blue carry the depth as red does.
uniform sampler2D depthtex0;
varying vec2 texcoord;
void main() {
    vec4 depth = texture2D(depthtex0, texcoord);
    gl_FragData[0] = vec4(depth.r, depth.g, 1.0 - depth.b, depth.a);
}
