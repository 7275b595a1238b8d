#version 330 compatibility
// The brightest channel through GL_AMD_shader_trinary_minmax's max3(), as
// Luracasmus/renderpearl calls it where the driver offers it: AMD's and Mesa's drivers do;
// NVIDIA's, Intel's on Windows and macOS do not, and refuse the stage.
#extension GL_AMD_shader_trinary_minmax : enable
uniform sampler2D colortex0;
in vec2 texcoord;
/* DRAWBUFFERS:0 */
void main() {
    vec3 colour = texture(colortex0, texcoord).rgb;
    float brightest = max3(colour.r, colour.g, colour.b);
    gl_FragData[0] = vec4(colour / max(brightest, 1e-4), 1.0);
}
