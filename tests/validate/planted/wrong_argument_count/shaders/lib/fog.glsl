vec3 fogify(vec3 color, float dist) {
	return mix(color, vec3(0.7), clamp(dist / 64.0, 0.0, 1.0));
}
