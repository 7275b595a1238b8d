#version 400 compatibility
// Local arrays sized by local constants, one initialised from a global that is not folded.
in vec2 uv;
const vec3[2] coefficients = vec3[2](vec3(1.0), mix(vec3(0.0), vec3(1.0), 0.5));
vec3 fog(float d) {
	const int count = 3;
	const uint pairs = 2u;
	const vec3[count] attenuation = vec3[count](coefficients[0], coefficients[1], vec3(0.01));
	float[count] phase;
	float scratch[pairs];
	for (int i = 0; i < count; ++i) {
		phase[i] = d * attenuation[i].x;
	}
	scratch[1] = phase[2];
	return vec3(phase[0], phase[1], scratch[1]);
}
void main() {
	gl_FragData[0] = vec4(fog(uv.x), 1.0);
}
