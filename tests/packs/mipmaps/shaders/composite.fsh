#version 130
// A pattern finer than a pixel can blur: a one-pixel checker over the scene's colour.
uniform sampler2D colortex0;
in vec2 texcoord;
void main() {
    vec3 scene = texture(colortex0, texcoord).rgb;
    float checker = mod(floor(gl_FragCoord.x) + floor(gl_FragCoord.y), 2.0);
/* DRAWBUFFERS:2 */
    gl_FragData[0] = vec4(scene * checker, 1.0);
}
