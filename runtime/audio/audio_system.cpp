#include "audio/audio_system.h"

#include <AL/al.h>
#include <AL/alc.h>
#include <AL/alext.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace tumble::audio {

struct AudioSystem::Impl {
  ALCdevice* device = nullptr;
  ALCcontext* context = nullptr;
  LPALCRENDERSAMPLESSOFT renderSamples = nullptr;
  std::size_t renderedFrames = 0;
  /// One OpenAL context is current per process: every call that touches
  /// AL makes this system's current first (tests hold several systems).
  void current() const {
    if (context && alcGetCurrentContext() != context) alcMakeContextCurrent(context);
  }
};

namespace {

constexpr double kRate = kSampleRate_hz;
constexpr int kMaxOneShots = 24;  ///< impacts and thunder at once; more impacts are dropped

ALuint uploadBuffer(const Clip& clip) {
  ALuint buffer = 0;
  alGenBuffers(1, &buffer);
  alBufferData(buffer, AL_FORMAT_MONO16, clip.samples.data(), ALsizei(clip.samples.size() * sizeof(std::int16_t)),
               clip.rate_hz);
  return buffer;
}

/// OpenAL Soft probes its backends when opening the default device, and
/// ALSA prints a dozen lines to stderr for each card it cannot find. The
/// player gets one message from us instead: stderr is muted for the probe.
ALCdevice* openDefaultDeviceQuietly() {
  std::fflush(stderr);
  const int saved = dup(STDERR_FILENO), devNull = open("/dev/null", O_WRONLY);
  if (saved >= 0 && devNull >= 0) dup2(devNull, STDERR_FILENO);
  ALCdevice* device = alcOpenDevice(nullptr);
  if (saved >= 0 && devNull >= 0) dup2(saved, STDERR_FILENO);
  if (saved >= 0) close(saved);
  if (devNull >= 0) close(devNull);
  return device;
}

void setSourcePosition(ALuint s, const Vec3& p) { alSource3f(s, AL_POSITION, float(p.x()), float(p.y()), float(p.z())); }

}  // namespace

AudioSystem::AudioSystem(AudioOutput output) : m_output(output), m_impl(std::make_unique<Impl>()) {}

Result<std::unique_ptr<AudioSystem>> AudioSystem::create(AudioOutput output) {
  std::unique_ptr<AudioSystem> sys(new AudioSystem(output));
  Impl& im = *sys->m_impl;
  if (output == AudioOutput::Device) {
    im.device = openDefaultDeviceQuietly();
    if (!im.device) return makeError("no audio output device");
    const char* name = alcGetString(im.device, ALC_DEVICE_SPECIFIER);
    sys->m_deviceName = name ? name : "";
    // OpenAL Soft falls back to its null backend ("No Output") when nothing
    // else opens: that is no device for the player.
    if (sys->m_deviceName == "No Output") {
      alcCloseDevice(im.device);
      im.device = nullptr;
      return makeError("no audio output device");
    }
    im.context = alcCreateContext(im.device, nullptr);
  } else if (output == AudioOutput::Loopback) {
    if (!alcIsExtensionPresent(nullptr, "ALC_SOFT_loopback"))
      return makeError("this OpenAL has no loopback device (ALC_SOFT_loopback); offline audio needs OpenAL Soft");
    auto open = reinterpret_cast<LPALCLOOPBACKOPENDEVICESOFT>(alcGetProcAddress(nullptr, "alcLoopbackOpenDeviceSOFT"));
    im.device = open ? open(nullptr) : nullptr;
    if (!im.device) return makeError("OpenAL Soft could not open its loopback device");
    im.renderSamples = reinterpret_cast<LPALCRENDERSAMPLESSOFT>(alcGetProcAddress(im.device, "alcRenderSamplesSOFT"));
    sys->m_deviceName = "loopback";
    // Plain stereo panning, no HRTF and no output limiter: the render is a
    // linear mix, so loudness measured in it is what the sources were given.
    const ALCint attrs[] = {ALC_FORMAT_CHANNELS_SOFT, ALC_STEREO_SOFT, ALC_FORMAT_TYPE_SOFT, ALC_FLOAT_SOFT,
                            ALC_FREQUENCY, kSampleRate_hz, ALC_HRTF_SOFT, ALC_FALSE, ALC_OUTPUT_LIMITER_SOFT, ALC_FALSE, 0};
    im.context = alcCreateContext(im.device, attrs);
  } else {
    sys->m_deviceName = "";
  }
  if (output != AudioOutput::Silent) {
    if (!im.context) {
      alcCloseDevice(im.device);
      im.device = nullptr;
      return makeError("OpenAL could not create a context on the audio device");
    }
    im.current();
    alDistanceModel(AL_INVERSE_DISTANCE_CLAMPED);
  }
  sys->setVolumes({});
  sys->setListener(Vec3::Zero(), Vec3(0, 0, -1), Vec3(0, 1, 0), Vec3::Zero());
  if (output == AudioOutput::Silent) return sys;  // nothing is mixed: no need for the runtime's own sounds
  // The runtime's own sounds (synth.h).
  sys->m_engineLow = sys->addClip(clipFromFloat(engineLoop(false), kSampleRate_hz));
  sys->m_engineBright = sys->addClip(clipFromFloat(engineLoop(true), kSampleRate_hz));
  sys->m_wind = sys->addClip(clipFromFloat(windLoop(), kSampleRate_hz));
  sys->m_thunderClip = sys->addClip(clipFromFloat(thunderClip(), kSampleRate_hz));
  for (int s = 0; s < kTyreSurfaceCount; ++s)
    sys->m_tyre[s] = sys->addClip(clipFromFloat(tyreLoop(TyreSurface(s)), kSampleRate_hz));
  return sys;
}

AudioSystem::~AudioSystem() {
  if (!m_impl->context) return;
  m_impl->current();
  for (auto& [id, s] : m_sounds) alDeleteSources(1, &s.source);
  for (auto& [key, v] : m_vehicles) releaseVehicle(v);
  for (ALuint s : m_oneShots) alDeleteSources(1, &s);
  if (m_rainSource) alDeleteSources(1, &m_rainSource);
  for (ALuint b : m_buffers) alDeleteBuffers(1, &b);
  alcMakeContextCurrent(nullptr);
  alcDestroyContext(m_impl->context);
  alcCloseDevice(m_impl->device);
}

void AudioSystem::setVolumes(const AudioVolumes& v) {
  auto clamp01 = [](float x) { return std::isfinite(x) ? std::clamp(x, 0.0f, 1.0f) : 1.0f; };
  m_volumes = {clamp01(v.master), clamp01(v.effects), clamp01(v.engine)};
  if (!m_impl->context) return;
  m_impl->current();
  alListenerf(AL_GAIN, m_volumes.master);
  for (auto& [id, s] : m_sounds) applyGain(s.source, s.category, s.volume);
  applyGain(m_rainSource, SoundCategory::Effects, kRainGain * m_rainLevel);
}

void AudioSystem::setListener(const Vec3& p, const Vec3& forward, const Vec3& up, const Vec3& v) {
  m_listener_m = p;
  if (!m_impl->context) return;
  m_impl->current();
  alListener3f(AL_POSITION, float(p.x()), float(p.y()), float(p.z()));
  alListener3f(AL_VELOCITY, float(v.x()), float(v.y()), float(v.z()));
  const float orientation[6] = {float(forward.x()), float(forward.y()), float(forward.z()),
                                float(up.x()),      float(up.y()),      float(up.z())};
  alListenerfv(AL_ORIENTATION, orientation);
}

ClipId AudioSystem::addClip(const Clip& clip) {
  m_impl->current();
  m_buffers.push_back(m_impl->context ? uploadBuffer(clip) : 0);
  m_clipSeconds.push_back(clip.seconds());
  return ClipId(m_buffers.size());
}

Result<ClipId> AudioSystem::clipFromFile(const std::string& path) {
  if (auto it = m_fileClips.find(path); it != m_fileClips.end()) return it->second;
  auto clip = loadClip(path);
  if (!clip) return makeError(clip.error());
  const ClipId id = addClip(*clip);
  m_fileClips[path] = id;
  return id;
}

double AudioSystem::clipSeconds(ClipId clip) const {
  return clip >= 1 && clip <= m_clipSeconds.size() ? m_clipSeconds[clip - 1] : 0;
}

unsigned AudioSystem::newSource(ClipId clip, bool loop, const Vec3& position_m, float referenceDistance_m) {
  ALuint s = 0;
  alGenSources(1, &s);
  if (alGetError() != AL_NO_ERROR || s == 0) return 0;
  alSourcei(s, AL_BUFFER, ALint(m_buffers[clip - 1]));
  alSourcei(s, AL_LOOPING, loop ? AL_TRUE : AL_FALSE);
  alSourcef(s, AL_REFERENCE_DISTANCE, referenceDistance_m);
  setSourcePosition(s, position_m);
  return s;
}

void AudioSystem::applyGain(unsigned source, SoundCategory category, float volume) {
  if (!source) return;
  const float c = category == SoundCategory::Engine ? m_volumes.engine : m_volumes.effects;
  alSourcef(source, AL_GAIN, std::max(0.0f, volume * c));
}

Result<SoundId> AudioSystem::play(const SoundParams& p) {
  if (p.clip < 1 || p.clip > m_buffers.size()) return makeError("no such sound clip");
  if (!(p.volume >= 0) || !std::isfinite(p.volume)) return makeError("volume must be a finite number >= 0");
  if (!(p.pitch > 0) || !std::isfinite(p.pitch)) return makeError("pitch must be a finite number > 0");
  if (!p.position_m.allFinite()) return makeError("position must be finite");
  reapFinished();
  if (int(m_sounds.size()) >= kMaxSounds)
    return makeError(std::to_string(kMaxSounds) + " sounds are already playing (the limit); stop one first");
  Sound s;
  s.category = p.category;
  s.volume = p.volume;
  s.pitch = p.pitch;
  s.loop = p.loop;
  s.end_s = m_time_s + clipSeconds(p.clip) / p.pitch;
  if (m_impl->context) {
    m_impl->current();
    s.source = newSource(p.clip, p.loop, p.position_m, p.referenceDistance_m);
    if (!s.source) return makeError("OpenAL has no free source");
    alSourcef(s.source, AL_PITCH, p.pitch);
    if (p.atListener) {
      alSourcei(s.source, AL_SOURCE_RELATIVE, AL_TRUE);
      setSourcePosition(s.source, Vec3::Zero());
    }
    applyGain(s.source, s.category, s.volume);
    alSourcePlay(s.source);
  }
  const SoundId id = m_nextSound++;
  m_sounds.emplace(id, s);
  return id;
}

bool AudioSystem::isPlaying(SoundId id) const {
  auto it = m_sounds.find(id);
  if (it == m_sounds.end()) return false;
  if (!it->second.source) return it->second.loop || it->second.end_s > m_time_s;
  m_impl->current();
  ALint state = 0;
  alGetSourcei(it->second.source, AL_SOURCE_STATE, &state);
  return state == AL_PLAYING || state == AL_INITIAL;
}

void AudioSystem::setPitch(SoundId id, float pitch) {
  auto it = m_sounds.find(id);
  if (it == m_sounds.end() || !(pitch > 0) || !std::isfinite(pitch)) return;
  // A silent one-shot's end moves with its rate: the part left plays at the new pitch.
  it->second.end_s = m_time_s + std::max(0.0, it->second.end_s - m_time_s) * it->second.pitch / pitch;
  it->second.pitch = pitch;
  if (!it->second.source) return;
  m_impl->current();
  alSourcef(it->second.source, AL_PITCH, pitch);
}

void AudioSystem::setVolume(SoundId id, float volume) {
  auto it = m_sounds.find(id);
  if (it == m_sounds.end() || !(volume >= 0) || !std::isfinite(volume)) return;
  it->second.volume = volume;
  m_impl->current();
  applyGain(it->second.source, it->second.category, volume);
}

void AudioSystem::setPosition(SoundId id, const Vec3& p) {
  auto it = m_sounds.find(id);
  if (it == m_sounds.end() || !it->second.source || !p.allFinite()) return;
  m_impl->current();
  setSourcePosition(it->second.source, p);
}

void AudioSystem::setVelocity(SoundId id, const Vec3& v) {
  auto it = m_sounds.find(id);
  if (it == m_sounds.end() || !it->second.source || !v.allFinite()) return;
  m_impl->current();
  alSource3f(it->second.source, AL_VELOCITY, float(v.x()), float(v.y()), float(v.z()));
}

void AudioSystem::stop(SoundId id) {
  auto it = m_sounds.find(id);
  if (it == m_sounds.end()) return;
  if (it->second.source) {
    m_impl->current();
    alSourceStop(it->second.source);
    alDeleteSources(1, &it->second.source);
  }
  m_sounds.erase(it);
}

float AudioSystem::impactGain(float impulse_Ns) {
  if (!(impulse_Ns >= kImpactMin_Ns)) return 0;
  return std::min(1.0f, impulse_Ns / kImpactFull_Ns);
}

void AudioSystem::impact(const Vec3& position_m, float impulse_Ns, ImpactMaterial a, ImpactMaterial b) {
  const float gain = impactGain(impulse_Ns);
  if (gain <= 0 || !m_impl->context || int(m_oneShots.size()) >= kMaxOneShots || !position_m.allFinite()) return;
  if (int(a) >= kImpactMaterialCount) a = ImpactMaterial::Thud;
  if (int(b) >= kImpactMaterialCount) b = ImpactMaterial::Thud;
  if (a > b) std::swap(a, b);
  m_impl->current();
  ClipId& clip = m_impactPair[int(a)][int(b)];
  if (!clip) clip = addClip(clipFromFloat(impactClip(a, b), kSampleRate_hz));
  const ALuint s = newSource(clip, false, position_m, 8);
  if (!s) return;
  applyGain(s, SoundCategory::Effects, gain);
  alSourcePlay(s);
  m_oneShots.push_back(s);
}

double AudioSystem::thunder(const Vec3& position_m) {
  const double delay_s = (position_m - m_listener_m).norm() / kSpeedOfSound_mps;
  if (position_m.allFinite()) m_thunder.push_back({m_time_s + delay_s, position_m});
  return delay_s;
}

void AudioSystem::startThunder(const Vec3& position_m) {
  if (!m_impl->context || int(m_oneShots.size()) >= kMaxOneShots) return;
  m_impl->current();
  // Heard at full volume out to 1 km, then falling as 1 / distance.
  const ALuint s = newSource(m_thunderClip, false, position_m, 1000);
  if (!s) return;
  applyGain(s, SoundCategory::Effects, 1);
  alSourcePlay(s);
  m_oneShots.push_back(s);
}

void AudioSystem::setRain(float intensity) {
  m_rainTarget = std::isfinite(intensity) ? std::clamp(intensity, 0.0f, 1.0f) : 0.0f;
}

void AudioSystem::updateRain(double dt_s) {
  m_rainLevel += float((m_rainTarget - m_rainLevel) * (1.0 - std::exp(-dt_s / kRainFade_s)));
  if (m_rainTarget == 0 && m_rainLevel < 1e-4f) m_rainLevel = 0;  // -80 dB: done fading
  if (!m_impl->context || (!m_rainSource && m_rainLevel == 0)) return;
  m_impl->current();
  if (!m_rainSource) {
    if (!m_rainClip) m_rainClip = addClip(clipFromFloat(rainLoop(), kSampleRate_hz));
    m_rainSource = newSource(m_rainClip, true, Vec3::Zero(), 1);
    if (!m_rainSource) return;
    alSourcei(m_rainSource, AL_SOURCE_RELATIVE, AL_TRUE);  // at the listener wherever it goes
    applyGain(m_rainSource, SoundCategory::Effects, 0);
    alSourcePlay(m_rainSource);
  }
  applyGain(m_rainSource, SoundCategory::Effects, kRainGain * m_rainLevel);
}

float AudioSystem::tyreGain(float slip, float threshold) {
  if (!(slip > threshold)) return 0;
  return std::min(1.0f, (slip - threshold) / 6.0f);
}

void AudioSystem::releaseVehicle(VehicleVoices& v) {
  for (unsigned* s : {&v.engineLow, &v.engineBright, &v.sample, &v.wind, &v.tyres[0], &v.tyres[1], &v.tyres[2], &v.tyres[3]})
    if (*s) {
      alSourceStop(*s);
      alDeleteSources(1, s);
      *s = 0;
    }
}

void AudioSystem::updateVehicle(std::uint64_t key, const VehicleSoundInput& in) {
  auto [it, fresh] = m_vehicles.try_emplace(key);
  VehicleVoices& v = it->second;
  v.seen = true;
  if (!m_impl->context || !in.position_m.allFinite()) return;
  m_impl->current();
  auto loop = [&](unsigned& source, ClipId clip, float referenceDistance_m) {
    if (source) return;
    source = newSource(clip, true, in.position_m, referenceDistance_m);
    if (!source) return;
    alSourcef(source, AL_GAIN, 0);
    alSourcePlay(source);
  };
  if (fresh) {
    if (in.engineSample) {
      loop(v.sample, in.engineSample, 6);
    } else {
      loop(v.engineLow, m_engineLow, 6);
      loop(v.engineBright, m_engineBright, 6);
    }
    loop(v.wind, m_wind, 4);
    for (int s = 0; s < kTyreSurfaceCount; ++s) loop(v.tyres[s], m_tyre[s], 5);
  }
  // Gear change: the engine note dips while the clutch is open (smoothed
  // over a few updates so it does not click).
  v.dip += ((in.shifting ? 0.45f : 1.0f) - v.dip) * 0.35f;
  const float load = std::isfinite(in.load) ? std::clamp(in.load, 0.0f, 1.0f) : 0.0f;
  const float volume = std::isfinite(in.volume) ? std::max(0.0f, in.volume) : 0.0f;
  const double firing = firingFrequency_hz(std::isfinite(in.rpm) ? std::max(0.0f, in.rpm) : 0.0f, in.cylinders);
  auto place = [&](unsigned s) {
    if (!s) return;
    setSourcePosition(s, in.position_m);
    alSource3f(s, AL_VELOCITY, float(in.velocity_mps.x()), float(in.velocity_mps.y()), float(in.velocity_mps.z()));
  };
  for (unsigned s : {v.engineLow, v.engineBright, v.sample, v.wind, v.tyres[0], v.tyres[1], v.tyres[2], v.tyres[3]}) place(s);
  // Engine: louder and brighter with load.
  if (v.sample) {
    alSourcef(v.sample, AL_PITCH, std::clamp(float(in.rpm / std::max(1.0f, in.sampleRpm)), 0.05f, 8.0f));
    applyGain(v.sample, SoundCategory::Engine, volume * (0.6f + 0.4f * load) * v.dip);
  } else {
    const float pitch = std::clamp(float(firing / kEngineLoopBase_hz), 0.05f, 16.0f);
    alSourcef(v.engineLow, AL_PITCH, pitch);
    alSourcef(v.engineBright, AL_PITCH, pitch);
    applyGain(v.engineLow, SoundCategory::Engine, volume * (0.55f + 0.25f * load) * v.dip);
    applyGain(v.engineBright, SoundCategory::Engine, volume * (0.05f + 0.6f * load) * v.dip);
  }
  // Tyres: per surface, the wheels sliding on it (root of the sum of squares, at most 1).
  float sum2[kTyreSurfaceCount] = {};
  for (const auto& w : in.wheels)
    if (w.contact) sum2[int(w.surface)] += std::pow(tyreGain(w.slipSpeed_mps, in.tyreSlipThreshold_mps), 2.0f);
  for (int s = 0; s < kTyreSurfaceCount; ++s) applyGain(v.tyres[s], SoundCategory::Effects, std::min(1.0f, std::sqrt(sum2[s])));
  // Wind: grows with the square of the speed (dynamic pressure), full at 40 m/s.
  const float speed = std::isfinite(in.speed_mps) ? std::fabs(in.speed_mps) : 0.0f;
  applyGain(v.wind, SoundCategory::Effects, 0.8f * std::min(1.0f, (speed / 40.0f) * (speed / 40.0f)));
  alSourcef(v.wind, AL_PITCH, std::min(2.0f, 0.8f + speed / 80.0f));
}

void AudioSystem::reapFinished() {
  for (auto it = m_sounds.begin(); it != m_sounds.end();) {
    if (!isPlaying(it->first)) {
      if (it->second.source) alDeleteSources(1, &it->second.source);
      it = m_sounds.erase(it);
    } else {
      ++it;
    }
  }
  if (!m_impl->context) return;
  m_impl->current();
  std::erase_if(m_oneShots, [](ALuint s) {
    ALint state = 0;
    alGetSourcei(s, AL_SOURCE_STATE, &state);
    if (state == AL_PLAYING || state == AL_INITIAL) return false;
    alDeleteSources(1, &s);
    return true;
  });
}

void AudioSystem::renderFrames(std::size_t frames) {
  if (m_output != AudioOutput::Loopback || frames == 0) return;
  m_impl->current();
  const std::size_t cap = std::size_t(kMaxRenderSeconds * kRate) * 2;
  const std::size_t at = m_rendered.size();
  std::vector<float> scratch;
  float* out;
  if (at + frames * 2 <= cap) {
    m_rendered.resize(at + frames * 2);
    out = m_rendered.data() + at;
  } else {
    m_renderTruncated = true;  // keep mixing (sources advance), keep nothing
    scratch.resize(frames * 2);
    out = scratch.data();
  }
  m_impl->renderSamples(m_impl->device, out, ALCsizei(frames));
  m_impl->renderedFrames += frames;
}

void AudioSystem::update(double dt_s) {
  if (!(dt_s > 0) || !std::isfinite(dt_s)) return;
  const double end_s = m_time_s + dt_s;
  updateRain(dt_s);
  // Thunder due within this update starts on its own frame when rendering
  // offline (exact to a sample), at the update otherwise.
  std::sort(m_thunder.begin(), m_thunder.end(), [](auto& a, auto& b) { return a.due_s < b.due_s; });
  std::size_t started = 0;
  for (; started < m_thunder.size() && m_thunder[started].due_s < end_s; ++started) {
    const auto frame = std::size_t(std::llround(std::max(m_thunder[started].due_s, 0.0) * kRate));
    if (frame > m_impl->renderedFrames) renderFrames(frame - m_impl->renderedFrames);
    startThunder(m_thunder[started].position_m);
  }
  m_thunder.erase(m_thunder.begin(), m_thunder.begin() + std::ptrdiff_t(started));
  const auto endFrame = std::size_t(std::llround(end_s * kRate));
  if (m_output == AudioOutput::Loopback && endFrame > m_impl->renderedFrames) renderFrames(endFrame - m_impl->renderedFrames);
  m_time_s = end_s;
  m_impl->current();
  for (auto it = m_vehicles.begin(); it != m_vehicles.end();) {
    if (!it->second.seen) {
      releaseVehicle(it->second);
      it = m_vehicles.erase(it);
    } else {
      it->second.seen = false;
      ++it;
    }
  }
  reapFinished();
}

}  // namespace tumble::audio
