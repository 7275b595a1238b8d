#version 330 compatibility
// Constructs desktop drivers accept and naga does not, as released packs write them.
uniform float rainStrength;
uniform sampler2D tex;
uniform bool isRaining;
float sign_of_rain = rainStrength < 0.5 ? 1.0 : -1.0;
float dimmed=exp(-rainStrength);
vec2 offsets[2] = vec2[2](vec2(rainStrength), vec2(0.0)), scale = vec2(2.0);
const vec3[] palette = vec3[](vec3(1.0), vec3(0.5), vec3(0.25));
const float wet = 1.0 > 0.5 ? 0.75 : length(normalize(vec3(0.0)));
const float blend = mix(0.25, 0.75, 0.5);
const float rcpMax12 = 1.0 / (pow(2.0, 12.0) - 1.0);
out vec2 texcoord;
out float rain;
flat out vec3[2] tints;

float shade(const in float x, vec2 sampler) {
	return x * sampler.x;
};

vec4 fetch(sampler2D sampler, vec2 uv) {
	return texture2D(sampler, uv);
}

float lookup(vec2 uv) {
	vec4 tex = texture2D(tex, uv);
	bool isRaining = tex.a > 0.5;
	return isRaining ? tex.r : 0.0;
}

void main() {
	gl_Position = ftransform();
	tints = vec3[2](vec3(1.0), vec3(0.5));
	texcoord = gl_MultiTexCoord0.xy + offsets[0] * scale + vec2(float(gl_VertexID % 4));
	rain = shade(sign_of_rain, vec2(wet)) + palette[2].x + lookup(texcoord) + (isRaining ? 1.0 : 0.0) + blend * rcpMax12 + fetch(tex, texcoord).r;
}
