#version 130
uniform float frameTimeCounter;
const int noiseTextureResolution = 256;
out vec2 texcoord;
out float cycle;
float wave(vec2 sampler) {
	return sampler.x;
}
void main() {
	gl_Position = ftransform();
	texcoord = gl_MultiTexCoord0.xy;
	float whole;
	cycle = modf(frameTimeCounter + float(min(gl_VertexID, 1)), whole) + wave(texcoord) + float((ivec2(texcoord) % 4).x) + float((ivec2(texcoord) % noiseTextureResolution).y);
}
