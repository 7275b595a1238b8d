// Player options. OptiFine lists a #define here as an option in the shader menu; labels,
// comments, screens and profiles come from shaderpack/pack.toml.

#define WATER_WAVES // Move water surface vertices in a slow swell.
#define WAVE_AMPLITUDE 0.05 // [0.02 0.05 0.08] Height of the vertex swell in blocks.
#define CAUSTICS // Light patterns on surfaces under water.
#define CAUSTICS_STRENGTH 0.25 // [0.10 0.25 0.40 0.60] Brightness swing of the caustic pattern.
#define DEPTH_FADE // Deeper water hides what lies beneath it.
#define DEPTH_FADE_DISTANCE 12.0 // [6.0 8.0 12.0 16.0 24.0] Water depth in blocks at which the floor disappears.

// OptiFine shows a switch only when the file that defines it also tests it.
#ifdef WATER_WAVES
#endif
#ifdef CAUSTICS
#endif
#ifdef DEPTH_FADE
#endif
