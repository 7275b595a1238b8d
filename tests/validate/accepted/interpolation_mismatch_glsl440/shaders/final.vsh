#version 440 compatibility
out vec2 texcoord;
out vec3 tint;
void main() {
	gl_Position = ftransform();
	texcoord = gl_MultiTexCoord0.xy;
	tint = gl_Color.rgb;
}
