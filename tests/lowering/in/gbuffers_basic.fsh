#version 120

uniform sampler2D texture;
uniform sampler2D lightmap;

void main() {
	vec4 color = gl_Color * texture2D(texture, gl_TexCoord[0].st);
	color.rgb *= texture2D(lightmap, gl_TexCoord[1].st).rgb;
	gl_FragColor = color;
}
