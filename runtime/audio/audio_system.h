#pragma once
// AudioSystem: a scene's sound, on OpenAL Soft. Three outputs:
//   Device    the machine's default output (play);
//   Loopback  OpenAL Soft's loopback device (ALC_SOFT_loopback): the mix is
//             rendered into memory as simulated time advances, in step with
//             it (tests, `run --audio-out FILE.wav`); no sound card needed;
//   Silent    no OpenAL at all (a machine without an audio device, --mute,
//             headless runs): sounds are still checked, tracked and timed,
//             so scripts behave the same, but nothing is mixed.
// The listener follows the camera; sources sit at positions or bodies (the
// app moves them). Gains: master on the listener; effects or engine per source.
//
//   auto audio = AudioSystem::create(AudioOutput::Loopback).value();
//   audio->setListener({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, Vec3::Zero());
//   SoundId s = audio->play({.clip = audio->addClip(clip), .position_m = {3, 0, 0}}).value();
//   audio->update(1.0 / 60);   // advances time; Loopback renders 800 frames
//   audio->rendered();         // interleaved stereo floats at kSampleRate_hz
//
// Index: AudioOutput | SoundParams | VehicleSoundInput | AudioSystem
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "audio/clip.h"
#include "audio/synth.h"
#include "core/math.h"
#include "core/result.h"

namespace tumble::audio {

enum class AudioOutput { Device, Loopback, Silent };
enum class SoundCategory { Effects, Engine };

/// Gains 0..1 (the player's settings: volume_master, volume_effects, volume_engine).
struct AudioVolumes {
  float master = 1, effects = 1, engine = 1;
};

using ClipId = std::uint32_t;
/// A playing sound; 0 is none. Ids are never reused within a system.
using SoundId = std::uint64_t;

struct SoundParams {
  ClipId clip = 0;
  Vec3 position_m = Vec3::Zero();
  float volume = 1;  ///< gain, >= 0 (1: as recorded)
  float pitch = 1;   ///< playback rate, > 0 (2: an octave up, twice as fast)
  bool loop = false;
  SoundCategory category = SoundCategory::Effects;
  /// Distance up to which the sound is heard at full volume, m; beyond it
  /// the gain falls as reference / distance (OpenAL's inverse distance model).
  float referenceDistance_m = 5;
  /// At the listener wherever it goes (position_m ignored): not placed in the world.
  bool atListener = false;
};

/// What a vehicle's sound is made from, once per update.
struct VehicleSoundInput {
  Vec3 position_m = Vec3::Zero(), velocity_mps = Vec3::Zero();
  float rpm = 0;
  float load = 0;       ///< engine torque / full-throttle torque at this rpm, 0..1
  bool shifting = false;  ///< clutch open for a gear change: the engine dips
  float speed_mps = 0;  ///< through the air (wind)
  int cylinders = 4;    ///< firing frequency rpm / 60 * cylinders / 2
  float volume = 1;     ///< the vehicle's engine volume
  ClipId engineSample = 0;   ///< 0: synthesised; else a loop played at pitch rpm / sampleRpm
  float sampleRpm = 3000;    ///< rpm the sample was recorded at
  float tyreSlipThreshold_mps = 1.5f;  ///< contact-patch slip speed where tyre noise starts
  struct Wheel {
    bool contact = false;
    float slipSpeed_mps = 0;
    TyreSurface surface = TyreSurface::Asphalt;
  };
  std::vector<Wheel> wheels;
};

class AudioSystem {
 public:
  /// Device: fails when there is no output device (the caller falls back to
  /// Silent and says so once). Loopback fails only if OpenAL lacks it.
  static Result<std::unique_ptr<AudioSystem>> create(AudioOutput output);
  ~AudioSystem();
  AudioSystem(const AudioSystem&) = delete;
  AudioSystem& operator=(const AudioSystem&) = delete;

  AudioOutput output() const { return m_output; }
  /// The OpenAL device's name ("" when Silent).
  const std::string& deviceName() const { return m_deviceName; }

  void setVolumes(const AudioVolumes& v);
  const AudioVolumes& volumes() const { return m_volumes; }
  void setListener(const Vec3& position_m, const Vec3& forward, const Vec3& up, const Vec3& velocity_mps);
  const Vec3& listenerPosition() const { return m_listener_m; }

  /// Clips: file clips are cached by path (loaded once per system).
  ClipId addClip(const Clip& clip);
  Result<ClipId> clipFromFile(const std::string& path);
  double clipSeconds(ClipId clip) const;

  /// Starts a sound; an error when kMaxSounds are already playing.
  Result<SoundId> play(const SoundParams& params);
  bool isPlaying(SoundId id) const;
  void setPitch(SoundId id, float pitch);
  void setVolume(SoundId id, float volume);
  void setPosition(SoundId id, const Vec3& position_m);
  /// The sound's velocity, m/s: with the listener's, it gives the Doppler
  /// shift (OpenAL: f' = f (c - v_listener) / (c - v_source), the
  /// velocities' components from the source towards the listener,
  /// c = kOpenAlSpeedOfSound_mps).
  void setVelocity(SoundId id, const Vec3& velocity_mps);
  /// OpenAL's default speed of sound (AL_SPEED_OF_SOUND), used for the Doppler shift, m/s.
  static constexpr double kOpenAlSpeedOfSound_mps = 343.3;
  void stop(SoundId id);
  /// Sounds playing now (scripts' and impacts'; not the vehicles' voices).
  int playingCount() const { return int(m_sounds.size()); }
  static constexpr int kMaxSounds = 32;

  /// A collision of two materials (synth.h: each one's hit, summed): a
  /// one-shot whose amplitude is proportional to the normal impulse, full
  /// at kImpactFull_Ns, silent below kImpactMin_Ns.
  void impact(const Vec3& position_m, float impulse_Ns, ImpactMaterial a = ImpactMaterial::Thud,
              ImpactMaterial b = ImpactMaterial::Thud);
  static constexpr float kImpactMin_Ns = 5;
  static constexpr float kImpactFull_Ns = 3000;
  /// Gain of an impact of this impulse (before distance): impulse / kImpactFull_Ns, at most 1.
  static float impactGain(float impulse_Ns);

  /// Thunder of a lightning flash at position_m now: heard after the
  /// distance from the listener / kSpeedOfSound_mps. Returns that delay, s.
  double thunder(const Vec3& position_m);
  static constexpr double kSpeedOfSound_mps = 343;

  /// Rain on and around the listener (not placed in the world): intensity
  /// 0 (none) .. 1 (a storm's downpour). The level follows it smoothly, as
  /// level += (intensity - level) (1 - exp(-dt / kRainFade_s)) per update,
  /// and the rain loop plays at gain kRainGain * level (effects volume).
  void setRain(float intensity);
  float rainLevel() const { return m_rainLevel; }
  static constexpr double kRainFade_s = 2;
  static constexpr float kRainGain = 0.5f;

  /// A vehicle's engine, tyres and wind, keyed by the caller (one key per
  /// vehicle). Voices of vehicles not updated since the last update() stop.
  void updateVehicle(std::uint64_t key, const VehicleSoundInput& in);
  /// Gain of the tyre noise at this slip speed (0 at or below the threshold, 1 at threshold + 6 m/s).
  static float tyreGain(float slipSpeed_mps, float threshold_mps);
  /// Engine firing frequency, Hz: rpm / 60 * cylinders / 2.
  static double firingFrequency_hz(double rpm, int cylinders) { return rpm / 60.0 * cylinders / 2.0; }

  /// Advances the audio clock by dt_s: starts due thunder, drops finished
  /// sounds, stops vehicles not updated; Loopback renders dt_s of sound.
  void update(double dt_s);
  double time_s() const { return m_time_s; }

  /// Loopback: everything rendered so far, interleaved stereo at
  /// kSampleRate_hz (at most kMaxRenderSeconds; later sound is dropped).
  const std::vector<float>& rendered() const { return m_rendered; }
  static constexpr double kMaxRenderSeconds = 600;
  bool renderTruncated() const { return m_renderTruncated; }

 private:
  struct Impl;
  explicit AudioSystem(AudioOutput output);
  struct Sound {
    unsigned source = 0;  ///< OpenAL source, 0 when Silent
    SoundCategory category = SoundCategory::Effects;
    float volume = 1, pitch = 1;
    bool loop = false;
    double end_s = 0;  ///< Silent: when a one-shot ends
  };
  struct VehicleVoices {
    unsigned engineLow = 0, engineBright = 0, sample = 0, wind = 0;
    unsigned tyres[kTyreSurfaceCount] = {};
    bool seen = true;
    float dip = 1;  ///< gear-change dip, smoothed
  };
  struct PendingThunder {
    double due_s;
    Vec3 position_m;
  };
  unsigned newSource(ClipId clip, bool loop, const Vec3& position_m, float referenceDistance_m);
  void applyGain(unsigned source, SoundCategory category, float volume);
  void renderFrames(std::size_t frames);
  void startThunder(const Vec3& position_m);
  void updateRain(double dt_s);
  void releaseVehicle(VehicleVoices& v);
  void reapFinished();

  AudioOutput m_output;
  std::unique_ptr<Impl> m_impl;
  std::string m_deviceName;
  AudioVolumes m_volumes;
  Vec3 m_listener_m = Vec3::Zero();
  std::vector<unsigned> m_buffers;  ///< by ClipId - 1 (0 when Silent)
  std::vector<double> m_clipSeconds;
  std::map<std::string, ClipId> m_fileClips;
  ClipId m_engineLow = 0, m_engineBright = 0, m_wind = 0, m_thunderClip = 0, m_rainClip = 0;
  /// Impact clips by material pair [min][max], made on first use.
  ClipId m_impactPair[kImpactMaterialCount][kImpactMaterialCount] = {};
  float m_rainTarget = 0, m_rainLevel = 0;
  unsigned m_rainSource = 0;
  ClipId m_tyre[kTyreSurfaceCount] = {};
  std::unordered_map<SoundId, Sound> m_sounds;
  SoundId m_nextSound = 1;
  std::map<std::uint64_t, VehicleVoices> m_vehicles;
  std::vector<PendingThunder> m_thunder;
  std::vector<unsigned> m_oneShots;  ///< impacts and thunder, freed when done
  double m_time_s = 0;
  double m_renderDebt_frames = 0;
  std::vector<float> m_rendered;
  bool m_renderTruncated = false;
};

}  // namespace tumble::audio
