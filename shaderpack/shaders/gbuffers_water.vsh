#version 330 compatibility
// Translucent terrain (water, stained glass, ice, ...): classifies blocks by their id from
// block.properties and, for water, moves the surface in a slow swell.
#include "/lib/settings.glsl"
#include "/lib/common.glsl"
#include "/lib/space.glsl"
#include "/lib/generated.glsl"
#include "/lib/waves.glsl"

// `attribute`, which GLSL 330 compatibility keeps: OptiFine for Minecraft 1.16.5 and older binds
// mc_Entity only where a line declares it with that word.
attribute vec4 mc_Entity;

uniform mat4 gbufferModelView;
uniform mat4 gbufferModelViewInverse;
uniform vec3 cameraPosition;
uniform float frameTimeCounter;
uniform float far;

out vec2 texUv;
out vec2 lightUv;
out vec4 tint;
// 1 on water, 0 on every other translucent block.
out float waterBlock;
out vec3 viewPosition;

void main() {
    // Ids arrive as floats; unmapped blocks are -1.
    int blockId = int(floor(mc_Entity.x + 0.5));
    bool isWater = blockId == BLOCK_WATER;
    vec4 viewPos = gl_ModelViewMatrix * gl_Vertex;
#ifdef WATER_WAVES
    if (isWater) {
        vec3 playerPos = (gbufferModelViewInverse * viewPos).xyz;
        vec3 worldPos = playerPos + wrappedCamera(cameraPosition, SWELL_PERIOD);
        // Only the surface moves: vertices on block boundaries (the bottom of side faces)
        // stay, so the water never parts from the blocks around it.
        float heightInBlock = fract(playerPos.y + cameraPosition.y);
        if (heightInBlock > 0.01 && heightInBlock < 0.99) {
            float amplitude = WAVE_AMPLITUDE;
#ifdef DISTANT_HORIZONS
            // Distant Horizons' flat water goes on where the game's chunks end (a square of
            // side 2 × far): the swell dies out before it, so the two surfaces meet.
            amplitude *= 1.0 - smoothstep(0.75 * far, far, max(abs(playerPos.x), abs(playerPos.z)));
#endif
            playerPos.y += swellOffset(worldPos.z, frameTimeCounter, amplitude);
            viewPos = gbufferModelView * vec4(playerPos, 1.0);
        }
    }
#endif
    gl_Position = gl_ProjectionMatrix * viewPos;
    viewPosition = viewPos.xyz;
    texUv = (gl_TextureMatrix[0] * gl_MultiTexCoord0).xy;
    lightUv = (gl_TextureMatrix[1] * gl_MultiTexCoord1).xy;
    tint = gl_Color;
    waterBlock = isWater ? 1.0 : 0.0;
}
