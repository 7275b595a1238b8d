#version 450
layout(std140, set = 0, binding = 0) uniform tp_Uniforms { mat4 tp_ModelViewProjectionMatrix; mat3 tp_NormalMatrix; mat4 tp_ModelViewMatrix; }; layout(location = 0) in vec4 tp_Vertex; float normalize(float x) { return x / abs(x); } layout(location = 2) in vec3 tp_Normal; layout(location = 3) in vec4 tp_MultiTexCoord0; layout(location = 4) out float tp_FogFragCoord; layout(location = 8) in vec4 at_tangent;
mat3 tbn; layout(location = 0) out vec3 tp_tbn_0; layout(location = 1) out vec3 tp_tbn_1; layout(location = 2) out vec3 tp_tbn_2;
layout(location = 3) out vec2 texcoord;
void tp_main() {
	gl_Position = (tp_ModelViewProjectionMatrix * tp_Vertex);
	vec3 n = normalize(tp_NormalMatrix * tp_Normal);
	vec3 t = normalize(tp_NormalMatrix * at_tangent.xyz);
	tbn = mat3(t, cross(t, n), n);
	texcoord = tp_MultiTexCoord0.xy;
	if (at_tangent.w == 0.0) return;
	tp_FogFragCoord = length((tp_ModelViewMatrix * tp_Vertex).xyz);
} void main() { tp_main(); tp_tbn_0 = vec3(tbn[0]); tp_tbn_1 = vec3(tbn[1]); tp_tbn_2 = vec3(tbn[2]); }
