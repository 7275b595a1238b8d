#version 450
layout(std140, set = 0, binding = 0) uniform tp_Uniforms { mat4 tp_ModelViewProjectionMatrix; mat4 tp_TextureMatrix[8]; }; layout(location = 0) in vec4 tp_Vertex; layout(location = 0) out vec4 tp_FrontColor; layout(location = 1) in vec4 tp_Color; layout(location = 1) out vec4 tp_TexCoord0; layout(location = 3) in vec4 tp_MultiTexCoord0; layout(location = 2) out vec4 tp_TexCoord1; layout(location = 4) in vec4 tp_MultiTexCoord1; 
void main() {
	gl_Position = tp_ModelViewProjectionMatrix * tp_Vertex;
	tp_FrontColor = tp_Color;
	tp_TexCoord0 = tp_TextureMatrix[0] * tp_MultiTexCoord0;
	tp_TexCoord1 = tp_TextureMatrix[1] * tp_MultiTexCoord1;
}
