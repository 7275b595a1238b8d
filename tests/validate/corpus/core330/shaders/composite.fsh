#version 330 compatibility
#include "/lib/tonemap.glsl"
uniform sampler2D colortex0;
uniform sampler2D colortex4;
in vec2 uv;
/* RENDERTARGETS: 0 */
layout(location = 0) out vec4 fragColor;
const vec2 taps[4] = vec2[4](vec2(-1.0, 0.0), vec2(1.0, 0.0), vec2(0.0, -1.0), vec2(0.0, 1.0));
void main() {
	vec3 c = texture(colortex0, uv).rgb;
	if (texture(colortex4, uv).r > 0.5) {
		vec3 blurred = c;
		for (int i = 0; i < 4; i++) blurred += texture(colortex0, uv + taps[i] * 0.002).rgb;
		blurred += textureOffset(colortex0, uv, ivec2(1, 1)).rgb - textureOffset(colortex0, uv, ivec2(-1, -1)).rgb;
		c = blurred / 5.0;
	}
	fragColor = vec4(tonemap(c), 1.0);
}
