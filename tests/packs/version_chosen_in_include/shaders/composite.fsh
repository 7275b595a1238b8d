#include "/lib/version.glsl"
uniform sampler2D colortex0;
varying vec2 texcoord;
void main() {
    gl_FragData[0] = vec4(texture2D(colortex0, texcoord).rgb * 0.5, 1.0);
}
