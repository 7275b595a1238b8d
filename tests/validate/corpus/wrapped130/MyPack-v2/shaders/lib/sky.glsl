uniform vec3 skyColor;
uniform vec3 fogColor;
uniform vec3 upPosition;
uniform mat4 gbufferProjectionInverse;
uniform float viewWidth, viewHeight;

vec3 skyGradient(vec3 viewDir) {
	float up = dot(viewDir, normalize(upPosition));
	return mix(fogColor, skyColor, smoothstep(-0.1, 0.4, up));
}
