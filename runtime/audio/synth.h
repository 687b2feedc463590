#pragma once
// The sounds the runtime makes itself, synthesised once per audio system
// into short mono buffers that OpenAL loops and re-pitches (no sample files
// to ship). Every buffer is deterministic (a fixed seed per kind), so an
// offline render is the same on every run.
//
//   engineLoop   harmonics of a kEngineLoopBase_hz firing pulse: played at
//                pitch firing_hz / kEngineLoopBase_hz, firing_hz =
//                rpm / 60 * cylinders / 2 (a four-stroke fires each cylinder
//                every second turn). The "low" layer has harmonic k at 1/k
//                (the fundamental strongest); the "bright" layer adds
//                harmonics 2..20 and combustion noise, faded in with load.
//   tyreLoop     the noise of a sliding tyre, per surface: asphalt squeal
//                (tonal partials near 1.1 kHz), gravel crunch (random
//                clicks band-passed near 2.5 kHz), grass swish (noise above
//                4 kHz), mud squelch (noise below 250 Hz with slow bubbles).
//   windLoop     low band-passed noise with gusts.
//   impactClip   two materials struck together: the sum of each one's hit
//                (impactMaterialName lists them; synth.cpp defines each as
//                resonant modes with their decay times and a noise burst).
//   rainLoop     broadband hiss (noise high-passed at 500 Hz, low-passed
//                twice at 5 kHz: most power at 1..8 kHz) with drops
//                (short pings at 1.5..6 kHz, about 300 a second).
//   thunderClip  a crack (noise above 1 kHz, 0.15 s) then a low rumble
//                (noise below 150 Hz with swells) dying over ~5 s.
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace tumble::audio {

/// Sample rate of everything the audio module makes and renders, Hz.
constexpr int kSampleRate_hz = 48000;
/// Fundamental of the engine loop buffers, Hz (48000 / 50 = 960 samples a cycle).
constexpr double kEngineLoopBase_hz = 50;

enum class TyreSurface { Asphalt = 0, Gravel, Grass, Mud };
constexpr int kTyreSurfaceCount = 4;
const char* tyreSurfaceName(TyreSurface s);

/// What a struck thing is made of (a body's sound material, the terrain's
/// sound layer). Thud: a body of no stated material (a dull 70 Hz knock).
enum class ImpactMaterial : std::uint8_t { Thud = 0, Metal, Wood, Rubber, Rock, Gravel, Soil, Mud };
constexpr int kImpactMaterialCount = 8;
/// "thud", "metal", "wood", "rubber", "rock", "gravel", "soil", "mud".
const char* impactMaterialName(ImpactMaterial m);
std::optional<ImpactMaterial> parseImpactMaterial(std::string_view name);

/// Peak-normalised (0.9) mono buffers at kSampleRate_hz. Loops join without a click.
std::vector<float> engineLoop(bool bright);
std::vector<float> tyreLoop(TyreSurface surface);
std::vector<float> windLoop();
std::vector<float> impactClip(ImpactMaterial a = ImpactMaterial::Thud, ImpactMaterial b = ImpactMaterial::Thud);
std::vector<float> rainLoop();
std::vector<float> thunderClip();

}  // namespace tumble::audio
