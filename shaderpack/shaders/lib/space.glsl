// Coordinate spaces. OptiFine's matrices are OpenGL's: window depth d in [0, 1] is NDC
// z = 2d - 1, and the inverse projection undoes the perspective divide.

// Perspective divide that stays finite: w is 0 only for points in the camera plane.
vec3 divideByW(vec4 p) {
    float w = abs(p.w) > 1e-7 ? p.w : (p.w < 0.0 ? -1e-7 : 1e-7);
    return p.xyz / w;
}

vec3 viewFromScreen(vec2 screenUv, float depth, mat4 projectionInverse) {
    return divideByW(projectionInverse * vec4(vec3(screenUv, depth) * 2.0 - 1.0, 1.0));
}

// Screen position (uv, depth) of a clip-space point; z < 0 when the point is behind the camera.
vec3 screenFromClip(vec4 clip) {
    if (clip.w <= 1e-5) {
        return vec3(-1.0);
    }
    return clip.xyz / clip.w * 0.5 + 0.5;
}

// The view-space point at window depth `depth` on the screen position of the view-space point
// viewPos, whose clip-space position is clip (w > 0). The inverse projection is linear, so that
// is viewPos moved along the inverse's depth column: no matrix product.
vec3 viewAtDepth(vec3 viewPos, vec4 clip, float depth, mat4 projectionInverse) {
    return divideByW(vec4(viewPos, 1.0) + projectionInverse[2] * ((2.0 * depth - 1.0) * clip.w - clip.z));
}

// Window depth of the point `distance` blocks from the eye along the view ray through uv.
float depthAtDistance(vec2 screenUv, float distance, mat4 projection, mat4 projectionInverse) {
    vec3 ray = safeNormalize(viewFromScreen(screenUv, 0.5, projectionInverse), vec3(0.0, 0.0, -1.0));
    vec4 clip = projection * vec4(ray * max(distance, 0.0), 1.0);
    return clamp(divideByW(clip).z * 0.5 + 0.5, 0.0, 1.0);
}

// Position relative to the player's eye, in world axes.
vec3 playerFromView(vec3 viewPos, mat4 modelViewInverse) {
    return mat3(modelViewInverse) * viewPos + modelViewInverse[3].xyz;
}

// Camera position modulo a power-of-two period. cameraPosition can be 3e7 blocks from the
// origin, where a float has a spacing of 2: reducing it modulo a power of two is exact, so
// patterns with that period stay seamless and their lookups stay precise.
vec3 wrappedCamera(vec3 cameraPosition, float period) {
    return cameraPosition - period * floor(cameraPosition / period);
}
