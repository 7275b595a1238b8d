vec3 saturate3(vec3 x) { return clamp(x, 0.0, 1.0); }
