#version 450
layout(std140, set = 0, binding = 0) uniform tp_Uniforms { float rainStrength; int tp_bool_isRaining; mat4 tp_ModelViewProjectionMatrix; }; float tp_rt_normalize(float a0) { return sign(a0); } vec2 tp_rt_normalize(vec2 a0) { return normalize(a0); } vec3 tp_rt_normalize(vec3 a0) { return normalize(a0); } vec4 tp_rt_normalize(vec4 a0) { return normalize(a0); } layout(location = 0) in vec4 tp_Vertex; layout(location = 3) in vec4 tp_MultiTexCoord0; 

layout(set = 0, binding = 1) uniform texture2D tex; layout(set = 0, binding = 2) uniform sampler tp_sampler_tex;

float sign_of_rain ; float tp_init_sign_of_rain() { return  rainStrength < 0.5 ? 1.0 : -1.0; }
float dimmed; float tp_init_dimmed() { return exp(-rainStrength); }
vec2 offsets[2] ; vec2[2] tp_init_offsets() { return  vec2[2](vec2(rainStrength), vec2(0.0)); } vec2 scale = vec2(2.0);
const vec3[3] palette = vec3[3](vec3(1.0), vec3(0.5), vec3(0.25));
 float wet ; float tp_init_wet() { return  1.0 > 0.5 ? 0.75 : length(tp_rt_normalize(vec3(0.0))); }
 float blend ; float tp_init_blend() { return  mix(0.25, 0.75, 0.5); }
const float rcpMax12 = 1.0 / (pow(2.0, 12.0) - 1.0);
layout(location = 1) out vec2 texcoord;
layout(location = 0) out float rain;
layout(location = 2) flat out vec3 tints[2];

float shade( in float x, vec2 tp_kw_sampler) {
	return x * tp_kw_sampler.x;
}

vec4 fetch(texture2D tp_kw_sampler, sampler tp_sampler_tp_kw_sampler, vec2 uv) {
	return textureLod(sampler2D(tp_kw_sampler, tp_sampler_tp_kw_sampler), uv, 0.0);
}

float lookup(vec2 uv) {
	vec4 tex = textureLod(sampler2D(tex, tp_sampler_tex), uv, 0.0);
	bool isRaining = tex.a > 0.5;
	return isRaining ? tex.r : 0.0;
}

void tp_main() {
	gl_Position = (tp_ModelViewProjectionMatrix * tp_Vertex);
	tints = vec3[2](vec3(1.0), vec3(0.5));
	texcoord = tp_MultiTexCoord0.xy + offsets[0] * scale + vec2(float(int(gl_VertexIndex) % 4));
	rain = shade(sign_of_rain, vec2(wet)) + palette[2].x + lookup(texcoord) + ((tp_bool_isRaining != 0) ? 1.0 : 0.0) + blend * rcpMax12 + fetch(tex, tp_sampler_tex, texcoord).r;
} void main() { sign_of_rain = tp_init_sign_of_rain(); dimmed = tp_init_dimmed(); offsets = tp_init_offsets(); wet = tp_init_wet(); blend = tp_init_blend(); tp_main(); }
