#version 450
layout(std140, set = 1, binding = 0) uniform tp_Uniforms { vec3 skyColor; }; float normalize(float x) { return x / abs(x); } float dot(float x, float y) { return x * y; } 
layout(set = 1, binding = 1) uniform texture2D gtexture; layout(set = 1, binding = 2) uniform sampler tp_sampler_gtexture;
layout(set = 1, binding = 3) uniform texture2D lightmap; layout(set = 1, binding = 4) uniform sampler tp_sampler_lightmap;


layout(location = 4) centroid in vec2 texcoord;
layout(location = 2) in vec2 lmcoord;
layout(location = 1) smooth in vec4 glcolor;
layout(location = 5) in vec3 viewPos;
layout(location = 3) noperspective in vec2 screenPos;
layout(location = 0) flat in int blockId;


layout(location = 0) out vec4 outColor0;
layout(location = 1) out vec4 outColor1;

void main() {
	vec4 color = texture(sampler2D(gtexture, tp_sampler_gtexture), texcoord) * glcolor;
	color.rgb *= texture(sampler2D(lightmap, tp_sampler_lightmap), lmcoord).rgb;
	if (blockId == 10008) {
		vec3 normal = normalize(cross(dFdx(viewPos), dFdy(viewPos)));
		float fresnel = pow(1.0 - abs(dot(normal, normalize(-viewPos))), 5.0);
		color.rgb = mix(color.rgb, skyColor, fresnel);
	}
	outColor0 = color;
	outColor1 = vec4(lmcoord, screenPos.x * 0.0, 1.0);
}
