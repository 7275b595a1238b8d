#version 120
struct Light {
	vec3 color;
	float strength;
};
uniform Light sun;
varying vec3 lightColors[2];
varying float zfog;
varying vec4 color;
void main() {
	vec3 c = (lightColors[0] + lightColors[1]) * sun.color * sun.strength + gl_SecondaryColor.rgb;
	gl_FragColor = vec4(c * zfog, 1.0) * color;
}
