#version 450
layout(std140, set = 0, binding = 0) uniform tp_Uniforms { mat4 tp_ModelViewProjectionMatrix; }; layout(location = 0) in vec4 tp_Vertex; layout(location = 3) in vec4 tp_MultiTexCoord0; 
layout(location = 0) out vec2 texcoord;

void main() {
	gl_Position = (tp_ModelViewProjectionMatrix * tp_Vertex);
	texcoord = tp_MultiTexCoord0.xy;
}
