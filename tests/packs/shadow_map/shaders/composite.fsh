#version 120
// Every way a pack reads the shadow map: shadowtex0 compared in hardware (with the water),
// shadowtex1 read as depth (without it), and both shadow colour buffers. Sky pixels land
// outside the shadow volume, where the reference depth passes 1.
const int shadowMapResolution = 512;
const float shadowDistance = 48.0;
const bool shadowHardwareFiltering = true;
const vec4 shadowcolor1ClearColor = vec4(0.0, 0.0, 0.0, 1.0);
uniform sampler2D colortex0;
uniform sampler2D depthtex0;
uniform sampler2DShadow shadowtex0;
uniform sampler2D shadowtex1;
uniform sampler2D shadowcolor0;
uniform sampler2D shadowcolor1;
uniform mat4 gbufferProjectionInverse;
uniform mat4 gbufferModelViewInverse;
uniform mat4 shadowModelView;
uniform mat4 shadowProjection;
varying vec2 texcoord;
void main() {
    float depth = texture2D(depthtex0, texcoord).r;
    vec4 view = gbufferProjectionInverse * vec4(vec3(texcoord, depth) * 2.0 - 1.0, 1.0);
    vec4 player = gbufferModelViewInverse * vec4(view.xyz / view.w, 1.0);
    vec4 shadowClip = shadowProjection * shadowModelView * player;
    vec3 shadowPos = shadowClip.xyz / shadowClip.w * 0.5 + 0.5;
    float bias = 0.01;
    float lit = shadow2D(shadowtex0, vec3(shadowPos.xy, shadowPos.z - bias)).r;
    // A ramp, not a step: a step flips on the last bit at shadow edges, which no renderer fixes.
    float litWithoutWater = clamp((texture2D(shadowtex1, shadowPos.xy).r - shadowPos.z) * 50.0 + 1.0, 0.0, 1.0);
    vec3 caster = texture2D(shadowcolor0, shadowPos.xy).rgb;
    float waterAbove = texture2D(shadowcolor1, shadowPos.xy).r;
    vec3 color = texture2D(colortex0, texcoord).rgb;
    vec3 shaded = color * (0.4 + 0.3 * lit + 0.3 * litWithoutWater) + 0.2 * caster * (1.0 - lit) * waterAbove;
/* DRAWBUFFERS:0 */
    gl_FragData[0] = vec4(shaded, 1.0);
}
