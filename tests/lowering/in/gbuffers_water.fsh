#version 330 compatibility

uniform sampler2D gtexture;
uniform sampler2D lightmap;
uniform vec3 skyColor;

centroid in vec2 texcoord;
in vec2 lmcoord;
smooth in vec4 glcolor;
in vec3 viewPos;
noperspective in vec2 screenPos;
flat in int blockId;

/* RENDERTARGETS: 0,1 */
out vec4 outColor0;
out vec4 outColor1;

void main() {
	vec4 color = texture(gtexture, texcoord) * glcolor;
	color.rgb *= texture(lightmap, lmcoord).rgb;
	if (blockId == 10008) {
		vec3 normal = normalize(cross(dFdx(viewPos), dFdy(viewPos)));
		float fresnel = pow(1.0 - abs(dot(normal, normalize(-viewPos))), 5.0);
		color.rgb = mix(color.rgb, skyColor, fresnel);
	}
	outColor0 = color;
	outColor1 = vec4(lmcoord, screenPos.x * 0.0, 1.0);
}
