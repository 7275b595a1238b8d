#version 330 compatibility
flat out vec3[2] skyColours;
out vec2 texcoord;
void main() {
	skyColours = vec3[2](vec3(0.2, 0.4, 0.8), vec3(1.0));
	texcoord = gl_MultiTexCoord0.st;
	gl_Position = ftransform();
}
