#version 330 compatibility
uniform int worldTime;
in vec2 texcoord;
float dayFraction() {
	return worldTime % 24000;
}
void main() {
	gl_FragData[0] = vec4(texcoord, dayFraction() / 24000.0, 1.0);
}
