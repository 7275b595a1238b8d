// Screen-space reflections (docs/water-model.md A3): march the reflected ray through view space
// against the opaque depth buffer; on a miss the caller falls back to the sky.

// Returns the reflected scene colour in rgb and its weight in a (0 on a miss).
vec4 traceReflection(sampler2D sceneColor, sampler2D opaqueDepth, vec3 start, vec3 dir, float cosToNormal,
                     mat4 projection, mat4 projectionInverse) {
    // The ray's clip-space position is linear along it: one multiply-add a step.
    vec4 clipStart = projection * vec4(start, 1.0);
    vec4 clipDir = projection * vec4(dir, 0.0);
    // Steps grow along the ray; steep rays take shorter ones.
    float stepLength = 7.0 / max(0.6, cosToNormal * cosToNormal);
    float travelled = 0.5 * stepLength;
    float previous = 0.0;
    // Hit tolerance: squared distance, widening by 1.1 per step.
    float tolerance = 16.0;
    for (int i = 0; i < SSR_STEPS; i++) {
        vec3 p = start + dir * travelled;
        vec4 clip = clipStart + clipDir * travelled;
        vec3 screen = screenFromClip(clip);
        if (screen.z < 0.0 || any(lessThan(screen.xy, vec2(0.0))) || any(greaterThan(screen.xy, vec2(1.0)))) {
            // Behind the camera or off screen: nothing more to find.
            return vec4(0.0);
        }
        vec3 scene = viewAtDepth(p, clip, texture(opaqueDepth, screen.xy).r, projectionInverse);
        vec3 gap = scene - p;
        if (dot(gap, gap) < tolerance && p.z <= scene.z + 0.5) {
            // Bisect between the last miss and this hit on which side of the scene the ray is.
            float lo = previous;
            float hi = travelled;
            for (int j = 0; j < SSR_REFINE_STEPS; j++) {
                float mid = 0.5 * (lo + hi);
                vec3 q = start + dir * mid;
                vec4 qClip = clipStart + clipDir * mid;
                vec3 qScene = viewAtDepth(q, qClip, texture(opaqueDepth, screenFromClip(qClip).xy).r, projectionInverse);
                if (q.z < qScene.z) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            vec3 hit = screenFromClip(clipStart + clipDir * hi);
            vec2 ndc = clamp(hit.xy, 0.0, 1.0) * 2.0 - 1.0;
            // Fade towards the screen border, where the reflected scene ends.
            float border = clamp(1.0 - sqrt(sqrt(0.01 + dot(ndc, ndc))), 0.0, 1.0);
            return vec4(texture(sceneColor, clamp(hit.xy, 0.0, 1.0)).rgb, border);
        }
        previous = travelled;
        tolerance *= 1.1;
        stepLength *= 1.2;
        travelled += stepLength;
    }
    return vec4(0.0);
}
