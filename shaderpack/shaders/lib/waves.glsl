// The wave field (docs/water-model.md A1, A2) and the vertex swell.
//
// Everything repeats every WAVE_TILE blocks in x and z, the size the water texture covers,
// so world positions are taken relative to the camera wrapped by WAVE_TILE (space.glsl).
// Time rates are whole cycles per 3600 s, the period after which frameTimeCounter wraps.

const float WAVE_TILE = 64.0;

// Vertex swell: period 4 blocks along z, about 0.3 rad/s.
const float SWELL_PERIOD = 4.0;
const float SWELL_SPEED = TAU * 172.0 / 3600.0;

float swellOffset(float worldZ, float time, float amplitude) {
    return amplitude * sin(SWELL_SPEED * time + TAU / SWELL_PERIOD * worldZ);
}

// Analytic trochoid-like wave: 3 and 5 cycles per tile in x and z (wavelength about 11
// blocks), about 0.31 rad/s.
const vec2 WAVE_VECTOR = vec2(3.0, 5.0) * (TAU / WAVE_TILE);
const float WAVE_SPEED = TAU * 180.0 / 3600.0;
const float WAVE_AMPLITUDE_ANALYTIC = 0.10;
// Weight of the height texture relative to the analytic wave.
const float WAVE_NOISE_WEIGHT = 0.6;
const float WAVE_MAX_HEIGHT = WAVE_AMPLITUDE_ANALYTIC * (1.0 + WAVE_NOISE_WEIGHT);
// The height texture drifts by whole tiles per 3600 s.
const vec2 WAVE_DRIFT = vec2(36.0, 24.0) / 3600.0;

float wavePhase(vec2 worldXZ, float time) {
    return WAVE_SPEED * time + dot(WAVE_VECTOR, worldXZ);
}

// The analytic wave sin(θ − cos(θ)/2) at up to four phases θ given by their sines and cosines,
// and the cosine of its argument, which its slope needs. The shift cos(θ)/2 stays within ±0.5
// rad, where the series below are exact to float precision: a sample costs the sine and cosine
// of θ alone, and samples at fixed offsets from one phase need no trigonometry of their own.
vec4 analyticWave(vec4 sinPhase, vec4 cosPhase, out vec4 cosArgument) {
    vec4 shift = 0.5 * cosPhase;
    vec4 s2 = shift * shift;
    vec4 sinShift = shift * (1.0 - s2 / 6.0 * (1.0 - s2 / 20.0 * (1.0 - s2 / 42.0)));
    vec4 cosShift = 1.0 - s2 / 2.0 * (1.0 - s2 / 12.0 * (1.0 - s2 / 30.0 * (1.0 - s2 / 56.0)));
    cosArgument = cosPhase * cosShift + sinPhase * sinShift;
    return sinPhase * cosShift - cosPhase * sinShift;
}

// The first octave's height cross texel at a wrapped world position (see waveNormal). Its B is
// the height texture's R byte for byte, so the surface search reads the height from it, and
// the lookup where the search stops is the normal's first one.
vec4 heightCrossTexel(sampler2D heightCross1, vec2 worldXZ, float time) {
    vec2 uv = 0.5 + vec2(worldXZ.x, -worldXZ.y) / WAVE_TILE + time * WAVE_DRIFT;
    return texture(heightCross1, fract(uv));
}

// Height of the water surface above its flat plane, in blocks, given the height texture there
// and the analytic wave.
float waveHeight(float heightTexture, float analytic) {
    float noise = heightTexture * 2.0 - 1.0;
    return WAVE_AMPLITUDE_ANALYTIC * (analytic + WAVE_NOISE_WEIGHT * noise);
}

// The gradient of waveHeight (blocks per block along x and z) where the wave's phase has sine
// sinPhase and its argument cosine cosArgument, and the first height cross texel is crossTexel:
// the analytic wave's exactly, the height texture's as its difference across the texel's cross
// (±0.25 block, as waveNormal takes it).
vec2 waveGradient(vec4 crossTexel, float sinPhase, float cosArgument) {
    const float BIAS = 128.0 / 255.0;
    vec2 analytic = cosArgument * (1.0 + 0.5 * sinPhase) * WAVE_VECTOR;
    vec2 difference = vec2(crossTexel.r - BIAS, BIAS - crossTexel.g);
    return WAVE_AMPLITUDE_ANALYTIC * (analytic + WAVE_NOISE_WEIGHT * 2.0 * difference / 0.5);
}

// What the surface search evaluated at the point it returned, for waveNormal to reuse: the first
// octave's height cross texel and the sine and cosine of the wave's phase there. `evaluated` is
// false when the search ran out of steps before meeting the surface.
struct SurfaceSample {
    vec4 heightCross;
    float sinPhase;
    float cosPhase;
    bool evaluated;
};

// How much the height texture's ripples pulse along x and z at `time`: the same for every
// pixel, so the full-screen vertex stage works it out once.
vec2 ripplePulse(float time) {
    float travel = WAVE_SPEED * time;
    return 1.0 + 0.3 * vec2(cos(travel), sin(travel));
}

// Height error below which the search stops early. Against the converged reference, 0.0005
// block leaves every profile's error unchanged; 0.002 already cost ULTRA 6 dB PSNR.
const float SURFACE_TOLERANCE = 0.0005;
// A Newton step shorter than LANDING_STEP blocks from a gap under LANDING_GAP lands within
// SURFACE_TOLERANCE: its error is the gap times the gradient's relative error (the texture
// term's slope is a difference across ±0.25 block) plus the surface's curvature over the step,
// both well under the tolerance there. The landing point reuses the last texel, at most
// LANDING_STEP blocks away: a twelfth of a texel.
const float LANDING_GAP = 0.004;
const float LANDING_STEP = 0.02;

// A1: the wave surface along the view ray from the rasterised (flat) hit, `t` blocks along the
// ray: Newton's search kept inside the bracket where the crossing must lie (3.2 blocks either
// way). Each point on the camera's side of the surface moves the bracket's near end up to it,
// each one past the surface its far end; the next point is where the surface's tangent along the
// ray meets it, or the bracket's middle where that falls outside. The gradient costs no lookup
// (waveGradient reads it from the lookup of the height), and a smooth surface is met in 2 or 3
// lookups where the secant took 3 or 4.
// `playerHit` is relative to the eye; `cameraWrap` turns it into a wrapped world position.
// `atSurface` holds what was evaluated at the point returned.
vec3 refineSurface(sampler2D heightCross1, vec3 playerHit, vec3 rayDir, vec3 cameraWrap, float time, bool cameraAbove,
                   out SurfaceSample atSurface) {
    float planeY = playerHit.y;
    float near = -20.0 * WAVE_MAX_HEIGHT;
    float far = 20.0 * WAVE_MAX_HEIGHT;
    float t = 0.0;
    atSurface = SurfaceSample(vec4(0.0), 0.0, 1.0, false);
    for (int i = 0; i < WAVE_REFINE_STEPS; i++) {
        vec3 p = playerHit + rayDir * t;
        vec2 worldXZ = p.xz + cameraWrap.xz;
        vec4 crossTexel = heightCrossTexel(heightCross1, worldXZ, time);
        float phase = wavePhase(worldXZ, time);
        float sinPhase = sin(phase);
        float cosPhase = cos(phase);
        vec4 cosArgument;
        float analytic = analyticWave(vec4(sinPhase), vec4(cosPhase), cosArgument).x;
        float gap = p.y - planeY - waveHeight(crossTexel.b, analytic);
        // On the surface to within SURFACE_TOLERANCE: further steps cannot show.
        if (!NEEDED(abs(gap) >= SURFACE_TOLERANCE)) {
            atSurface = SurfaceSample(crossTexel, sinPhase, cosPhase, true);
            break;
        }
        if ((gap > 0.0) == cameraAbove) {
            near = t;
        } else {
            far = t;
        }
        // How the gap changes along the ray: the ray's vertical rate less the surface's rise
        // along it (Newton's step).
        float slope = rayDir.y - dot(waveGradient(crossTexel, sinPhase, cosArgument.x), rayDir.xz);
        float next = 0.5 * (near + far);
        bool landed = false;
        if (abs(slope) > 1e-6) {
            float crossing = t - gap / slope;
            bool inside = crossing >= near && crossing <= far;
            next = inside ? crossing : next;
            landed = inside && abs(gap) < LANDING_GAP && abs(gap / slope) < LANDING_STEP;
        }
        // A short Newton step from near the surface lands on it: take it without a lookup there,
        // handing waveNormal this point's texel and the phase moved along by the step.
        if (!NEEDED(!landed)) {
            float shift = dot(WAVE_VECTOR, rayDir.xz) * (next - t);
            float s2 = shift * shift;
            float sinShift = shift * (1.0 - s2 / 6.0);
            float cosShift = 1.0 - s2 / 2.0;
            atSurface = SurfaceSample(crossTexel, sinPhase * cosShift + cosPhase * sinShift, cosPhase * cosShift - sinPhase * sinShift, true);
            t = next;
            break;
        }
        t = next;
    }
    return playerHit + rayDir * t;
}

// A2: the surface normal (world axes, y up) at a wrapped world position, and the "diffuse
// intensity" that makes crests brighter than troughs. Far water is flattened against
// aliasing; the second octave is only worth it within 500 blocks.
//
// The height samples e = 0.25 blocks either side in x and z (one height texel at the first
// octave's scale, two at the second's) come from the height cross textures, one lookup per
// octave where the height itself would take four: per texel they hold the height's
// differences across the cross along u and v and the sum of its four ends, and bilinear
// filtering is linear, so a lookup of those is the difference (or sum) of the four lookups.
// `atSurface` is what refineSurface evaluated at worldXZ; `pulse` is ripplePulse(time).
vec3 waveNormal(sampler2D heightCross1, sampler2D heightCross2, vec2 worldXZ, float time, vec2 pulse, float distance,
                SurfaceSample atSurface, out float diffuse) {
    float flatten = 1.0 + 0.05 * distance;
    vec2 uv = 0.5 + vec2(worldXZ.x, -worldXZ.y) / WAVE_TILE + time * WAVE_DRIFT;
#if NORMAL_MODE == 0
    // One lookup, of the first height cross texel alone (see below): the height's differences
    // across the cross give the texture term's slope, B the height.
    const float BIAS = 128.0 / 255.0;
    vec4 cross1 = atSurface.heightCross;
    if (!atSurface.evaluated) {
        cross1 = texture(heightCross1, fract(uv));
    }
    vec2 slope = WAVE_AMPLITUDE_ANALYTIC * WAVE_NOISE_WEIGHT * 2.0 * vec2(cross1.r - BIAS, BIAS - cross1.g) / (2.0 * 0.25);
    diffuse = 0.35 + 0.4 * (cross1.b - 0.5);
    return safeNormalize(vec3(-slope.x, flatten, -slope.y), vec3(0.0, 1.0, 0.0));
#else
    const float e = 0.25;
    // The cross textures store differences and the neighbours' excess over the height biased
    // by 128/255. z runs along -v, so the difference along z is the one along v negated.
    const float BIAS = 128.0 / 255.0;
    vec4 cross1 = atSurface.heightCross;
    if (!atSurface.evaluated) {
        cross1 = texture(heightCross1, fract(uv));
    }
    vec2 difference = vec2(cross1.r - BIAS, BIAS - cross1.g);
    float heightSum = 4.0 * cross1.b + cross1.a - BIAS;
#if NORMAL_OCTAVES >= 2
    // The second octave doubles the frequency at 0.75 of the weight.
    if (distance < 500.0) {
        vec2 uv2 = 0.5 + 2.0 * vec2(worldXZ.x, -worldXZ.y) / WAVE_TILE + time * WAVE_DRIFT;
        vec4 cross2 = texture(heightCross2, fract(uv2));
        difference += 0.75 * vec2(cross2.r - BIAS, BIAS - cross2.g);
        heightSum += 0.75 * (4.0 * cross2.b + cross2.a - BIAS);
    }
#endif
    // A travelling phase lets the texture ripples pulse along x and z.
    float dx = difference.x * pulse.x;
    float dz = difference.y * pulse.y;
    // The analytic wave 2.1 blocks either side in x and z: phases at fixed offsets from this
    // point's, by the angle sum formulas.
    const vec4 OFFSET = vec4(WAVE_VECTOR.x, -WAVE_VECTOR.x, WAVE_VECTOR.y, -WAVE_VECTOR.y) * 2.1;
    float sinPhase = atSurface.sinPhase;
    float cosPhase = atSurface.cosPhase;
    if (!atSurface.evaluated) {
        float phase = wavePhase(worldXZ, time);
        sinPhase = sin(phase);
        cosPhase = cos(phase);
    }
    vec4 cosArgument;
    vec4 a = analyticWave(sinPhase * cos(OFFSET) + cosPhase * sin(OFFSET), cosPhase * cos(OFFSET) - sinPhase * sin(OFFSET), cosArgument);
    diffuse = 0.35 + 0.05 * heightSum + 0.05 * (a.x + a.y + a.z + a.w);
    // Height differences in blocks over the sample spacing: the normal of y = h(x, z).
    float slopeX = WAVE_AMPLITUDE_ANALYTIC * (WAVE_NOISE_WEIGHT * 2.0 * dx / (2.0 * e) + (a.x - a.y) / 4.2);
    float slopeZ = WAVE_AMPLITUDE_ANALYTIC * (WAVE_NOISE_WEIGHT * 2.0 * dz / (2.0 * e) + (a.z - a.w) / 4.2);
    return safeNormalize(vec3(-slopeX, flatten, -slopeZ), vec3(0.0, 1.0, 0.0));
#endif
}
