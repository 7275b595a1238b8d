#version 120
uniform sampler2D colortex0;
varying vec2 texcoord;
void main() {
	vec3 color = texture2D(colortex0, texcoord).rgb;
	color += 0.1 * texture(colortex0, texcoord * 0.5).rgb;
	gl_FragColor = vec4(color, 1.0);
}
