#version 130
// colortex2 read without mipmaps here: the checker itself.
uniform sampler2D colortex0;
uniform sampler2D colortex2;
in vec2 texcoord;
void main() {
    gl_FragColor = vec4(texture(colortex0, texcoord).rgb, texture(colortex2, texcoord).g);
}
