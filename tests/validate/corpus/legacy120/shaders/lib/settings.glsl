#ifndef SETTINGS_GLSL
#define SETTINGS_GLSL
#define SHADOWS // Shadows from the sun and moon
//#define DEBUG_NORMALS // Show normals instead of colours
#define WAVE_SPEED 1.0 // [0.5 1.0 2.0] How fast water waves move
#define SHADOW_SAMPLES 4 // [1 4 9] Shadow filter taps
#define FOG_STYLE 1 // [0 1 2] 0 none, 1 linear, 2 exponential
const int shadowMapResolution = 1024; // [512 1024 2048]
const float sunPathRotation = -30.0; // [-30.0 0.0 30.0]
#ifdef SHADOWS
#endif
#ifdef DEBUG_NORMALS
#endif
#endif
