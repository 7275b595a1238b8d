#version 450
layout(std140, set = 0, binding = 0) uniform tp_Uniforms { mat4 tp_ModelViewProjectionMatrix; mat4 tp_TextureMatrix[8]; }; layout(location = 0) in vec4 tp_Vertex; layout(location = 3) in vec4 tp_MultiTexCoord0; layout(location = 4) in vec4 tp_MultiTexCoord1; layout(location = 1) in vec4 tp_Color; 
layout(location = 2) out vec2 texcoord;
layout(location = 1) out vec2 lmcoord;
layout(location = 0) out vec4 glcolor;

void main() {
	gl_Position = (tp_ModelViewProjectionMatrix * tp_Vertex);
	texcoord = (tp_TextureMatrix[0] * tp_MultiTexCoord0).xy;
	lmcoord  = (tp_TextureMatrix[1] * tp_MultiTexCoord1).xy;
	glcolor = tp_Color;
}
