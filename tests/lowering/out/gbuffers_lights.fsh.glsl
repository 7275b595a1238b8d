#version 450
layout(location = 3) in vec4 tp_FrontSecondaryColor; layout(location = 0) out vec4 tp_FragData0; struct Light {
	vec3 color;
	float strength;
};
layout(std140, set = 1, binding = 1) uniform tp_Uniforms1 { Light sun; };
layout(location = 1) in vec3 lightColors[2];
layout(location = 4) in float zfog;
layout(location = 0) in vec4 color;
void main() {
	vec3 c = (lightColors[0] + lightColors[1]) * sun.color * sun.strength + tp_FrontSecondaryColor.rgb;
	tp_FragData0 = vec4(c * zfog, 1.0) * color;
}
