#version 450
layout(std140, set = 1, binding = 0) uniform tp_Uniforms { mat4 gbufferProjectionInverse; mat4 gbufferModelViewInverse; mat4 shadowModelView; mat4 shadowProjection; }; layout(location = 0) out vec4 tp_FragData0; 



const int shadowMapResolution = 2048;

layout(set = 1, binding = 1) uniform texture2D colortex0; layout(set = 1, binding = 2) uniform sampler tp_sampler_colortex0;
layout(set = 1, binding = 3) uniform texture2D depthtex0; layout(set = 1, binding = 4) uniform sampler tp_sampler_depthtex0;
layout(set = 1, binding = 5) uniform texture2D shadowtex0; layout(set = 1, binding = 6) uniform samplerShadow tp_sampler_shadowtex0;





layout(location = 0) in vec2 texcoord;

vec3 toShadowSpace(vec2 coord, float depth) {
	vec4 view = gbufferProjectionInverse * vec4(vec3(coord, depth) * 2.0 - 1.0, 1.0);
	vec4 world = gbufferModelViewInverse * vec4(view.xyz / view.w, 1.0);
	vec4 shadowPos = shadowProjection * (shadowModelView * world);
	float distortion = mix(1.0, length(shadowPos.xy), 0.85);
	shadowPos.xy /= distortion;
	return shadowPos.xyz * 0.5 + 0.5;
}

void main() {
	vec3 color = texture(sampler2D(colortex0, tp_sampler_colortex0), texcoord).rgb;
	float depth = texture(sampler2D(depthtex0, tp_sampler_depthtex0), texcoord).r;
	if (depth < 1.0) {
		vec3 shadowPos = toShadowSpace(texcoord, depth);
		float lit = vec4(vec3(texture(sampler2DShadow(shadowtex0, tp_sampler_shadowtex0), vec3(shadowPos.xy, shadowPos.z - 0.0005))), 1.0).r;
		color *= mix(0.4, 1.0, lit);
	}


	tp_FragData0 = vec4(color, 1.0);
}
