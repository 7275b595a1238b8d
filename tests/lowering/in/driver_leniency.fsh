#version 330 compatibility
uniform sampler2D specular;
in vec2 texcoord;
in float rain;
flat in vec3 tints[1 + 1];
uniform int frameCounter;
float gain = rain * 2.0;
float frames = frameCounter;

float fade(float specular);
float fade(float specular);
float fade(float specular) {
	return specular * 0.5;
}

float fade(float specular);

int brightest(vec3 color) {
	for (int i = 0; i < 2; i++) {
		if (color[i] >= color[2]) return i;
	}
}

float ticks(int worldTime) {
	int day = worldTime % 24000;
	float hours = day / 1000;
	return hours;
}

// A function declared first and defined after one it calls: GLSL allows it, naga wants
// callees first.
float lift(float x);
float doubled(float x) {
	return lift(x) * 2.0;
}
float raise(float x) {
	return x + 1.0;
}
float lift(float x) {
	return raise(x);
}

// Initializer lists (GLSL 4.20), which naga lacks.
float weights[3] = { 0.5, 1.0, 0.5 };
const vec2 pairs[] = { { 1.0, 2.0 }, { 3.0, 4.0 }, };

float gathered(vec2 uv) {
	vec3 scale = { 1.0, 2.0, 3.0 };
	return textureGather(specular, uv).x * weights[1] + textureGather(specular, uv, 1).y * pairs[1].y * scale.z;
}

// A struct field named like a sampler, and statements after a `return`.
struct Surface { float specular; };
float surfaced(float x) {
	Surface s;
	s.specular = x;
	return s.specular;
	return fade(x);
}

void main() {
	float whole;
	float part = modf(rain, whole);
	float specular = texture2D(specular, texcoord).r;
	float sample = fade(specular) + gathered(texcoord) + doubled(rain);
	gl_FragData[0] = vec4(sample * gain + part + whole + dot(rain, rain) + ticks(int(rain)) + frames + float(brightest(vec3(rain))) + tints[1].x + surfaced(rain));
}
