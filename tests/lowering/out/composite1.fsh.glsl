#version 450
layout(std140, set = 1, binding = 0) uniform tp_Uniforms { float viewWidth; float viewHeight; }; layout(location = 0) out vec4 tp_FragData0; 

layout(set = 1, binding = 1) uniform texture2D colortex0; layout(set = 1, binding = 2) uniform sampler tp_sampler_colortex0;
layout(set = 1, binding = 3) uniform texture2D colortex1; layout(set = 1, binding = 4) uniform sampler tp_sampler_colortex1;



layout(location = 0) in vec2 texcoord;

vec3 sampleLod(texture2D tex, sampler tp_sampler_tex, vec2 coord, float lod);

vec3 blur(texture2D tex, sampler tp_sampler_tex, vec2 coord, vec2 direction) {
	vec2 pixel = direction / vec2(viewWidth, viewHeight);
	vec3 sum = sampleLod(tex, tp_sampler_tex, coord, 0.0) * 0.4;
	for (int i = 1; i <= 3; i++) {
		sum += texture(sampler2D(tex, tp_sampler_tex), coord + pixel * float(i)).rgb * 0.1;
		sum += texture(sampler2D(tex, tp_sampler_tex), coord - pixel * float(i)).rgb * 0.1;
	}
	return sum;
}

vec3 sampleLod(texture2D tex, sampler tp_sampler_tex, vec2 coord, float lod) {
	return textureLod(sampler2D(tex, tp_sampler_tex), coord, lod).rgb;
}

vec3 combine(texture2D base, sampler tp_sampler_base, vec2 coord, texture2D glow, sampler tp_sampler_glow, float strength) {
	return texture(sampler2D(base, tp_sampler_base), coord).rgb + sampleLod(glow, tp_sampler_glow, coord, 2.0) * strength;
}

void main() {
	vec3 color = blur(colortex0, tp_sampler_colortex0, texcoord, vec2(1.0, 0.0));
	color += combine(colortex0, tp_sampler_colortex0, texcoord, colortex1, tp_sampler_colortex1, 0.1) * 0.0;
	vec3 bloom = sampleLod(colortex1, tp_sampler_colortex1, texcoord, 2.0) + blur(colortex1, tp_sampler_colortex1, texcoord, vec2(0.0, 1.0));


	tp_FragData0 = vec4(color + bloom * 0.1, 1.0);
}
