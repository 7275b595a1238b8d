#version 460 compatibility
// GLSL 4.60 (NVIDIA's and AMD's drivers offer it; Mesa's llvmpipe stops at 4.50).
out vec2 texcoord;
void main() {
	gl_Position = ftransform();
	texcoord = gl_MultiTexCoord0.xy;
}
