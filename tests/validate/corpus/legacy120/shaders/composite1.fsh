#version 120
#extension GL_ARB_shader_texture_lod : enable
#include "/lib/util/math.glsl"
uniform sampler2D colortex0;
uniform float viewWidth;
uniform float viewHeight;
uniform float fadeIn;
varying vec2 texcoord;
const bool colortex0MipmapEnabled = true;
vec3 blur(sampler2D image, vec2 coord) {
	vec2 px = 1.0 / vec2(viewWidth, viewHeight);
	vec3 sum = vec3(0.0);
	for (int x = -1; x <= 1; x++)
		for (int y = -1; y <= 1; y++)
			sum += texture2DLod(image, coord + vec2(x, y) * px, 1.0).rgb;
	return sum / 9.0;
}
void main() {
	vec2 c = rotate2(0.0) * (texcoord - 0.5) + 0.5;
	vec3 color = mix(texture2D(colortex0, c).rgb, blur(colortex0, c), 0.25 * saturate(fadeIn));
/* DRAWBUFFERS:0 */
	gl_FragData[0] = vec4(color, 1.0);
}
