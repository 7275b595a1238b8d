#version 120
varying vec2 uv;
uniform sampler2DShadow shadowtex0;
void main() {
    gl_FragData[0] = vec4(texture2D(shadowtex0, uv).r);
}
