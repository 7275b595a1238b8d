#include /lib/version.glsl
uniform sampler2D colortex0;
varying vec2 texcoord;
void main() {
    // MC_RENDER_STAGE_NONE is 0: a macro of the loader's, which the driver must see too.
    gl_FragData[0] = vec4(texture2D(colortex0, texcoord).rgb * 0.5, float(MC_RENDER_STAGE_NONE + 1));
}
