#version 450
layout(std140, set = 0, binding = 0) uniform tp_Uniforms { mat4 tp_ModelViewProjectionMatrix; }; layout(location = 0) in vec4 tp_Vertex; layout(location = 1) in vec4 tp_Color; layout(location = 29) in vec4 tp_SecondaryColor; layout(location = 25) in vec4 tp_MultiTexCoord4; layout(location = 30) in float tp_FogCoord; layout(location = 3) out vec4 tp_FrontSecondaryColor; layout(location = 1) out vec3 lightColors[2];
layout(location = 4) out float zfog;
layout(location = 0) out vec4 color;
void main() {
	gl_Position = (tp_ModelViewProjectionMatrix * tp_Vertex);
	lightColors[0] = vec3(1.0);
	lightColors[1] = vec3(0.5);
	zfog = 0.0;
	color = tp_Color * tp_SecondaryColor + tp_MultiTexCoord4 * tp_FogCoord;
	tp_FrontSecondaryColor = vec4(0.0);
}
