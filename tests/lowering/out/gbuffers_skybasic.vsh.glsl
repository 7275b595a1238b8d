#version 450
layout(std140, set = 0, binding = 0) uniform tp_Uniforms { float rainStrength; mat4 tp_ModelViewProjectionMatrix; }; layout(location = 0) in vec4 tp_Vertex; layout(location = 1) out vec4 tp_FrontColor; layout(location = 1) in vec4 tp_Color; 


layout(location = 0) out float starData;

void main() {
	gl_Position = (tp_ModelViewProjectionMatrix * tp_Vertex);
	tp_FrontColor = tp_Color;
	starData = float(tp_Color.r == tp_Color.g && tp_Color.g == tp_Color.b && tp_Color.r > 0.0) * (1.0 - rainStrength);
}
