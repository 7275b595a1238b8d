#version 330 compatibility

uniform sampler2D colortex0;
uniform sampler2D colortex1;
uniform sampler2D depthtex0;
uniform vec3 shadowLightPosition;
uniform mat4 gbufferProjectionInverse;

in vec2 texcoord;
flat in float sunVisibility;

/* RENDERTARGETS: 0,1,2 */
out vec4 outColor1;
out vec4 outColor0;
layout(location = 2) out vec4 specularData;

void main() {
	vec4 albedo = texture(colortex0, texcoord);
	vec3 normal = texture2D(colortex1, texcoord).xyz * 2.0 - 1.0;
	float depth = texture2D(depthtex0, texcoord).r;
	vec4 viewPos = gbufferProjectionInverse * vec4(vec3(texcoord, depth) * 2.0 - 1.0, 1.0);
	viewPos /= viewPos.w;
	float diffuse = max(dot(normal, normalize(shadowLightPosition)), 0.0) * sunVisibility;
	outColor0 = vec4(albedo.rgb * (0.3 + diffuse), albedo.a);
	outColor1 = vec4(normal * 0.5 + 0.5, 1.0);
	specularData = vec4(viewPos.xyz * 0.0, 1.0);
}
