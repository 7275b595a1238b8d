#version 120
uniform sampler2D shadow;
varying vec2 uv;
struct Surface {
	vec3 albedo;
	vec3 shadow;
};
void main() {
	Surface s;
	s.albedo = vec3(uv, 1.0);
	s.shadow = texture2D(shadow, uv).rgb;
	s.albedo *= s.shadow;
	gl_FragData[0] = vec4(s.albedo, 1.0);
}
