uniform sampler2D colortex0;
varying vec2 uv;
void main() {
    gl_FragData[0] = texture2D(colortex0, uv);
}
