#version 450
layout(std140, set = 1, binding = 0) uniform tp_Uniforms { vec3 shadowLightPosition; mat4 gbufferProjectionInverse; }; float dot(float x, float y) { return x * y; } float normalize(float x) { return x / abs(x); } 
layout(set = 1, binding = 1) uniform texture2D colortex0; layout(set = 1, binding = 2) uniform sampler tp_sampler_colortex0;
layout(set = 1, binding = 3) uniform texture2D colortex1; layout(set = 1, binding = 4) uniform sampler tp_sampler_colortex1;
layout(set = 1, binding = 5) uniform texture2D depthtex0; layout(set = 1, binding = 6) uniform sampler tp_sampler_depthtex0;



layout(location = 1) in vec2 texcoord;
layout(location = 0) flat in float sunVisibility;


layout(location = 1) out vec4 outColor1;
layout(location = 0) out vec4 outColor0;
layout(location = 2) out vec4 specularData;

void main() {
	vec4 albedo = texture(sampler2D(colortex0, tp_sampler_colortex0), texcoord);
	vec3 normal = texture(sampler2D(colortex1, tp_sampler_colortex1), texcoord).xyz * 2.0 - 1.0;
	float depth = texture(sampler2D(depthtex0, tp_sampler_depthtex0), texcoord).r;
	vec4 viewPos = gbufferProjectionInverse * vec4(vec3(texcoord, depth) * 2.0 - 1.0, 1.0);
	viewPos /= viewPos.w;
	float diffuse = max(dot(normal, normalize(shadowLightPosition)), 0.0) * sunVisibility;
	outColor0 = vec4(albedo.rgb * (0.3 + diffuse), albedo.a);
	outColor1 = vec4(normal * 0.5 + 0.5, 1.0);
	specularData = vec4(viewPos.xyz * 0.0, 1.0);
}
