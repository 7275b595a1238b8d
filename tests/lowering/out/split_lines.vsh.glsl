#version 450
layout(std140, set = 0, binding = 0) uniform tp_Uniforms { mat4 tp_ModelViewProjectionMatrix; }; layout(location = 0) in vec4 tp_Vertex; layout(location = 0) out vec4 tp_TexCoord0; layout(location = 3) in vec4 tp_MultiTexCoord0; void main() {
	gl_Position = (tp_ModelViewProjectionMatrix * tp_Vertex)
;
	tp_TexCoord0
 = tp_MultiTexCoord0;
}
