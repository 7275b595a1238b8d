#version 330 compatibility
#include "/lib/uniforms.glsl"
uniform sampler2D colortex0;
uniform sampler2D colortex1;
uniform sampler2D depthtex0;
uniform sampler2D noisetex;
in vec2 uv;
/* RENDERTARGETS: 0 */
layout(location = 0) out vec3 color;

const int noiseTextureResolution = 128;
const float ambientOcclusionLevel = 0.8;

float linearDepth(float d) {
	return (2.0 * near * far) / (far + near - (d * 2.0 - 1.0) * (far - near));
}

vec3 screenToView(vec3 screen) {
	vec4 v = gbufferProjectionInverse * vec4(screen * 2.0 - 1.0, 1.0);
	return v.xyz / v.w;
}

void main() {
	vec3 albedo = texture(colortex0, uv).rgb;
	vec3 normal = texture(colortex1, uv).xyz * 2.0 - 1.0;
	float depth = textureLod(depthtex0, uv, 0.0).r;
	vec3 view = screenToView(vec3(uv, depth));
	float ndl = max(dot(normal, normalize(sunPosition)), 0.0);
	float sky = float(eyeBrightnessSmooth.y) / 240.0;
	vec2 jitter = texture(noisetex, gl_FragCoord.xy / float(noiseTextureResolution)).xy;
	float ao = 1.0 - ambientOcclusionLevel * 0.1 * jitter.x;
	color = depth == 1.0 ? skyColor : albedo * (0.2 + ndl) * ao + skyColor * sky * 0.1 + 0.0 * linearDepth(depth) * view.z;
	color += float(frameCounter % 2) * 0.0;
}
