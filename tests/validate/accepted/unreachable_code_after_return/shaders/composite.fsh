#version 120
uniform sampler2D colortex0;
varying vec2 uv;
float square(float x) {
	return x * x;
}
// Statements after a `return` or `discard` never run; drivers still compile them.
float shade(float x) {
	return x;
	return square(x);
}
float weight(float x) {
	for (int i = 0; i < 4; i++) {
		if (x > 0.5) {
			break;
			x = square(x);
		}
		continue;
		x += square(x);
	}
	return x;
}
void main() {
	vec4 color = texture2D(colortex0, uv);
	if (color.a < 0.1) {
		discard;
		color.rgb = vec3(square(color.r));
	}
	gl_FragData[0] = color * shade(color.r) * weight(color.g);
	return;
	gl_FragData[0].r = square(color.g);
}
