#version 450
layout(std140, set = 1, binding = 0) uniform tp_Uniforms { int frameCounter; }; vec4 tp_gather(texture2D t, sampler s, vec2 p, ivec2 o, int c) { ivec2 last = textureSize(sampler2D(t, s), 0) - 1; ivec2 i = ivec2(floor(p * vec2(last + 1) - 0.5)) + o; vec4 t00 = texelFetch(sampler2D(t, s), clamp(i, ivec2(0), last), 0); vec4 t10 = texelFetch(sampler2D(t, s), clamp(i + ivec2(1, 0), ivec2(0), last), 0); vec4 t01 = texelFetch(sampler2D(t, s), clamp(i + ivec2(0, 1), ivec2(0), last), 0); vec4 t11 = texelFetch(sampler2D(t, s), clamp(i + ivec2(1, 1), ivec2(0), last), 0); return vec4(t01[c], t11[c], t10[c], t00[c]); } vec4 textureGather(texture2D t, sampler s, vec2 p) { return tp_gather(t, s, p, ivec2(0), 0); } vec4 textureGather(texture2D t, sampler s, vec2 p, int c) { return tp_gather(t, s, p, ivec2(0), c); } float modf(float x, out float i) { i = trunc(x); return x - i; } vec2 modf(vec2 x, out vec2 i) { i = trunc(x); return x - i; } vec3 modf(vec3 x, out vec3 i) { i = trunc(x); return x - i; } vec4 modf(vec4 x, out vec4 i) { i = trunc(x); return x - i; } layout(location = 0) out vec4 tp_FragData0; float dot(float x, float y) { return x * y; } layout(set = 1, binding = 1) uniform texture2D specular; layout(set = 1, binding = 2) uniform sampler tp_sampler_specular;
layout(location = 1) in vec2 texcoord;
layout(location = 0) in float rain;
layout(location = 2) flat in vec3 tints[1+1];

float gain ; float tp_init_gain() { return  rain * 2.0; }
float frames ; float tp_init_frames() { return  frameCounter; }

float fade(float specular);

float fade(float specular) {
	return specular * 0.5;
}



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


float weights[3] ; float[3] tp_init_weights() { return  float[3]( 0.5, 1.0, 0.5 ); }
const vec2 pairs[2] = vec2[2]( vec2( 1.0, 2.0 ), vec2( 3.0, 4.0 ) );

float gathered(vec2 uv) {
	vec3 scale = vec3( 1.0, 2.0, 3.0 );
	return textureGather(specular, tp_sampler_specular, uv).x * weights[1] + textureGather(specular, tp_sampler_specular, uv, 1).y * pairs[1].y * scale.z;
}


struct Surface { float specular; };
float surfaced(float x) {
	Surface s;
	s.specular = x;
	if (true) return s.specular;
	return fade(x);
}

void tp_main() {
	float whole;
	float part = modf(rain, whole);
	float specular = texture(sampler2D(specular, tp_sampler_specular), texcoord).r;
	float tp_kw_sample = fade(specular) + gathered(texcoord) + doubled(rain);
	tp_FragData0 = vec4(tp_kw_sample * gain + part + whole + dot(rain, rain) + ticks(int(rain)) + frames + float(brightest(vec3(rain))) + tints[1].x + surfaced(rain));
} void main() { gain = tp_init_gain(); frames = tp_init_frames(); weights = tp_init_weights(); tp_main(); }
