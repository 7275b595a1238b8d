#version 330 compatibility
#define NETHER
#include "/lib/tonemap.glsl"
uniform sampler2D colortex0;
in vec2 uv;
/* RENDERTARGETS: 0 */
out vec4 outColor0;
void main() {
	vec3 c = texture(colortex0, uv).rgb;
#ifdef NETHER
	c *= vec3(1.0, 0.6, 0.5);
#endif
	outColor0 = vec4(tonemap(c), 1.0);
}
