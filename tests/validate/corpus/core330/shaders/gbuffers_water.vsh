#version 330 compatibility
uniform float frameTimeCounter;
in vec4 mc_Entity;
out vec2 texcoord;
out vec4 tint;
out float isWater;
void main() {
	vec4 pos = gl_Vertex;
	isWater = float(abs(mc_Entity.x - 10008.0) < 0.5);
	pos.y += isWater * sin(frameTimeCounter + pos.x) * 0.03;
	gl_Position = gl_ModelViewProjectionMatrix * pos;
	texcoord = gl_MultiTexCoord0.xy;
	tint = gl_Color;
}
