#version 450
struct tp_FogParameters { vec4 color; float density; float start; float end; float scale; }; layout(std140, set = 1, binding = 0) uniform tp_Uniforms { int tp_bool_isNight; float fogEnd; tp_FogParameters tp_Fog; }; layout(location = 4) in float tp_FogFragCoord; layout(location = 0) out vec4 tp_FragData0; layout(set = 1, binding = 1) uniform texture2D normals; layout(set = 1, binding = 2) uniform sampler tp_sampler_normals;


mat3 tbn; layout(location = 0) in vec3 tp_tbn_0; layout(location = 1) in vec3 tp_tbn_1; layout(location = 2) in vec3 tp_tbn_2;
layout(location = 3) in vec2 texcoord;
void tp_main() {
	vec3 n = tbn * (texture(sampler2D(normals, tp_sampler_normals), texcoord).xyz * 2.0 - 1.0);
	float fog = clamp((tp_Fog.end - tp_FogFragCoord) * tp_Fog.scale, 0.0, 1.0);
	vec3 color = mix(tp_Fog.color.rgb, n * 0.5 + 0.5, fog);
	if ((tp_bool_isNight != 0)) color *= 0.5;

	tp_FragData0 = vec4(color * fogEnd / 100.0, 1.0);
} void main() { tbn = mat3x3(tp_tbn_0, tp_tbn_1, tp_tbn_2); tp_main(); }
