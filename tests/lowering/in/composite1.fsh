#version 120
#extension GL_ARB_shader_texture_lod : enable

uniform sampler2D colortex0;
uniform sampler2D colortex1;
uniform float viewWidth;
uniform float viewHeight;

varying vec2 texcoord;

vec3 sampleLod(sampler2D tex, vec2 coord, float lod);

vec3 blur(sampler2D tex, vec2 coord, vec2 direction) {
	vec2 pixel = direction / vec2(viewWidth, viewHeight);
	vec3 sum = sampleLod(tex, coord, 0.0) * 0.4;
	for (int i = 1; i <= 3; i++) {
		sum += texture2D(tex, coord + pixel * float(i)).rgb * 0.1;
		sum += texture2D(tex, coord - pixel * float(i)).rgb * 0.1;
	}
	return sum;
}

vec3 sampleLod(sampler2D tex, vec2 coord, float lod) {
	return texture2DLod(tex, coord, lod).rgb;
}

vec3 combine(sampler2D base, vec2 coord, sampler2D glow, float strength) {
	return texture2D(base, coord).rgb + sampleLod(glow, coord, 2.0) * strength;
}

void main() {
	vec3 color = blur(colortex0, texcoord, vec2(1.0, 0.0));
	color += combine(colortex0, texcoord, colortex1, 0.1) * 0.0;
	vec3 bloom = sampleLod(colortex1, texcoord, 2.0) + blur(colortex1, texcoord, vec2(0.0, 1.0));

/* DRAWBUFFERS:0 */
	gl_FragData[0] = vec4(color + bloom * 0.1, 1.0);
}
