#version 120
uniform sampler2D colortex0;
varying vec2 uv;
float exposure = ;
void main() {
    gl_FragColor = texture2D(colortex0, uv) * exposure;
}
