// Player options. OptiFine lists each #define here in the shader menu; labels, comments,
// screens and the LOW / MEDIUM / HIGH / ULTRA profiles come from shaderpack/pack.toml.

// Surface shape
#define WATER_WAVES // Move water surface vertices in a slow swell.
#define WAVE_AMPLITUDE 0.05 // [0.02 0.05 0.08] Height of the vertex swell in blocks.
#define WAVE_REFINE_STEPS 8 // [0 4 6 8 10 16 32] Bisection steps that find the wave surface along the view ray. 0 uses the flat surface.
#define NORMAL_MODE 1 // [0 1] 0: the height texture's slopes from one lookup. 1: normals from height samples.
#define NORMAL_OCTAVES 2 // [1 2] Height octaves for normals; the second adds detail near the camera.

// Light on and through the surface
#define REFLECTIONS // Screen-space reflections; the sky is reflected where they miss.
#define SSR_STEPS 10 // [6 10 16 24] March steps of the screen-space reflection.
#define SSR_REFINE_STEPS 2 // [0 2 4 6] Bisection steps that sharpen a reflection hit.
#define SPECULAR // Sun, moon and sky highlights on the water.
#define FRESNEL_EXACT // Exact dielectric Fresnel instead of Schlick's approximation.
#define REFRACTION // Distort what is seen through the surface.
#define REFRACTION_STRENGTH 0.04 // [0.02 0.04 0.06 0.10] Screen distance of the refraction offset.

// Water volume
#define DEPTH_FADE // Light is absorbed along its way through water.
#define ABSORPTION_MODEL 1 // [0 1] 0: clamped linear ramp. 1: Beer-Lambert per colour channel.
#define DEPTH_FADE_DISTANCE 48.0 // [12.0 24.0 48.0 96.0] Path in blocks after which the ramp model has absorbed everything.
#define ABSORPTION_DENSITY 1.0 // [0.5 1.0 2.0 5.0 10.0] Beer-Lambert density as a multiple of pure water.
#define CAUSTICS // Light patterns on surfaces under water.
#define CAUSTICS_MODE 0 // [0 1] 0: two samples of the water height texture. 1: two samples of the noise texture.
#define CAUSTIC_SAMPLES 3 // [1 2 3] Sample pairs of the caustic pattern, each at a finer scale.
#define CAUSTICS_STRENGTH 0.40 // [0.10 0.25 0.40 0.60] Brightness of the caustic pattern.
#define FOAM // Foam on crests and along shores.
#define FAR_HAZE // Distant water fades into the fog colour.

// Performance
#define EARLY_OUTS // Skip work whose result cannot show. Off: the same picture, slower.

// OptiFine shows a switch only when the file that defines it also tests it.
#ifdef WATER_WAVES
#endif
#ifdef REFLECTIONS
#endif
#ifdef SPECULAR
#endif
#ifdef FRESNEL_EXACT
#endif
#ifdef REFRACTION
#endif
#ifdef DEPTH_FADE
#endif
#ifdef CAUSTICS
#endif
#ifdef FOAM
#endif
#ifdef FAR_HAZE
#endif

// NEEDED(condition) guards work a pixel can skip when the condition is false: a case of the
// water model the pixel is not in, or a contribution under 1/255. With EARLY_OUTS off every
// guard passes and the pixel does all the work, choosing its result afterwards as before: the
// same picture, which is what the early-outs are timed against (docs/skipping.md).
#ifdef EARLY_OUTS
#define NEEDED(condition) (condition)
#else
#define NEEDED(condition) true
#endif
