#version 120
#include "/lib/util/math.glsl"
uniform sampler2D colortex0;
varying vec2 texcoord;
void main() {
	vec3 color = texture2D(colortex0, texcoord).rgb;
	color = color / (1.0 + LUMA(color));
#if MC_VERSION >= 11700 && defined MC_GL_VENDOR_MESA
	color = pow(color, vec3(1.0 / 2.2));
#endif
	gl_FragColor = vec4(color * MC_RENDER_QUALITY, 1.0);
}
