#version 330 compatibility
uniform sampler2D colortex0;
// An input declared with the array type written before its name (`vec3[2] skyColours`).
flat in vec3[2] skyColours;
in vec2 texcoord;
const vec3 rayleighSunny = vec3(6.4e-6, 1.1e-5, 2.5e-5);
const vec3 rayleighRain = vec3(6.4e-5) * 2.0;
void main() {
	vec3 sky = mix(skyColours[0], skyColours[1], texcoord.y) * (rayleighSunny + rayleighRain) * 1e4;
	gl_FragData[0] = texture(colortex0, texcoord) + vec4(sky, 0.0);
}
