#version 120
uniform sampler2D texture;
uniform sampler2D lightmap;
void main() {
	vec4 c = texture2D(texture, gl_TexCoord[0].st) * texture2D(lightmap, gl_TexCoord[1].st) * gl_Color;
	float fog = clamp((gl_Fog.end - gl_FogFragCoord) * gl_Fog.scale, 0.0, 1.0);
	c.rgb = mix(gl_Fog.color.rgb, c.rgb, fog);
	gl_FragColor = c;
}
