#version 450
layout(std140, set = 0, binding = 0) uniform tp_Uniforms { mat4 tp_ModelViewMatrix; mat4 tp_ProjectionMatrix; }; layout(location = 0) in vec4 tp_Vertex; layout(location = 3) in vec4 tp_MultiTexCoord0; layout(location = 1) in vec4 tp_Color; 




layout(location = 8) in vec4 mc_Entity;

layout(location = 1) out vec2 texcoord;
layout(location = 0) out vec4 glcolor;

void main() {
	vec4 position = tp_ModelViewMatrix * tp_Vertex;
	gl_Position = tp_ProjectionMatrix * position;
	gl_Position.xyz = ((gl_Position.xyz) / mix(1.0, length((gl_Position.xyz).xy), 0.85));
	texcoord = tp_MultiTexCoord0.xy;
	glcolor = tp_Color;
	if (mc_Entity.x == 10008.0) gl_Position.w = -1.0;
}
