// Position reconstruction. OptiFine's matrices are OpenGL's: window depth d in [0, 1] is
// NDC z = 2d - 1, and the inverse projection undoes the perspective divide.

vec3 viewFromScreen(vec2 screenUv, float depth, mat4 projectionInverse) {
    vec4 view = projectionInverse * vec4(vec3(screenUv, depth) * 2.0 - 1.0, 1.0);
    // w is only 0 for a far plane at infinity; keep the sign and stay finite.
    float w = abs(view.w) > 1e-7 ? view.w : 1e-7;
    return view.xyz / w;
}

// Position relative to the player's eye, in world axes.
vec3 playerFromView(vec3 viewPos, mat4 modelViewInverse) {
    return mat3(modelViewInverse) * viewPos + modelViewInverse[3].xyz;
}

// Camera position reduced modulo a power-of-two period. cameraPosition can be 3e7 blocks
// from the origin, where a float has a spacing of 2; mod by a power of two is exact, and
// patterns with that period stay seamless.
vec3 wrappedCamera(vec3 cameraPosition, float period) {
    return cameraPosition - period * floor(cameraPosition / period);
}
