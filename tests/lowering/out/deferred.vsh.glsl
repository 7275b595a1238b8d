#version 450
layout(std140, set = 0, binding = 0) uniform tp_Uniforms { vec3 sunPosition; vec3 upPosition; mat4 tp_ModelViewProjectionMatrix; }; layout(location = 0) in vec4 tp_Vertex; layout(location = 3) in vec4 tp_MultiTexCoord0; float dot(float x, float y) { return x * y; } float normalize(float x) { return x / abs(x); } 



layout(location = 1) out vec2 texcoord;
layout(location = 0) flat out float sunVisibility;

void main() {
	gl_Position = tp_ModelViewProjectionMatrix * tp_Vertex;
	texcoord = tp_MultiTexCoord0.st;
	sunVisibility = clamp(dot(normalize(sunPosition), normalize(upPosition)) * 4.0, 0.0, 1.0);
}
