#version 120

#define SHADOW_BIAS 0.0005
#define SHADOW_DISTORTION 0.85

const int shadowMapResolution = 2048;

uniform sampler2D colortex0;
uniform sampler2D depthtex0;
uniform sampler2DShadow shadowtex0;
uniform mat4 gbufferProjectionInverse;
uniform mat4 gbufferModelViewInverse;
uniform mat4 shadowModelView;
uniform mat4 shadowProjection;

varying vec2 texcoord;

vec3 toShadowSpace(vec2 coord, float depth) {
	vec4 view = gbufferProjectionInverse * vec4(vec3(coord, depth) * 2.0 - 1.0, 1.0);
	vec4 world = gbufferModelViewInverse * vec4(view.xyz / view.w, 1.0);
	vec4 shadowPos = shadowProjection * (shadowModelView * world);
	float distortion = mix(1.0, length(shadowPos.xy), SHADOW_DISTORTION);
	shadowPos.xy /= distortion;
	return shadowPos.xyz * 0.5 + 0.5;
}

void main() {
	vec3 color = texture2D(colortex0, texcoord).rgb;
	float depth = texture2D(depthtex0, texcoord).r;
	if (depth < 1.0) {
		vec3 shadowPos = toShadowSpace(texcoord, depth);
		float lit = shadow2D(shadowtex0, vec3(shadowPos.xy, shadowPos.z - SHADOW_BIAS)).r;
		color *= mix(0.4, 1.0, lit);
	}

/* DRAWBUFFERS:0 */
	gl_FragData[0] = vec4(color, 1.0);
}
