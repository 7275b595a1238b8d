#version 130
// colortex2 read through its mipmaps, which the loader makes just before this program: level 4
// is the checker averaged over 16x16 pixels, half the scene's colour.
const bool colortex2MipmapEnabled = true;
uniform sampler2D colortex2;
in vec2 texcoord;
void main() {
/* DRAWBUFFERS:0 */
    gl_FragData[0] = vec4(textureLod(colortex2, texcoord, 4.0).rgb * 2.0, 1.0);
}
