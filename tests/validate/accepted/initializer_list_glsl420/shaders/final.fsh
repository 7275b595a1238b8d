#version 420 compatibility
uniform sampler2D colortex0;
in vec2 texcoord;
float weights[3] = { 0.25, 0.5, 0.25 };
const mat3 toneMatrix =
{
    { 0.59719, 0.35458, 0.04823 },
    { 0.07600, 0.90834, 0.01566 },
    { 0.02840, 0.13383, 0.83777 }
};
void main() {
	const vec2 offsets[] = { { -1.0, 0.0 }, { 0.0, 0.0 }, { 1.0, 0.0 } };
	vec4 sum = vec4(0.0);
	for (int i = 0; i < 3; i++) sum += texture(colortex0, texcoord + offsets[i] * 0.001) * weights[i];
	gl_FragData[0] = vec4(toneMatrix * sum.rgb, sum.a);
}
