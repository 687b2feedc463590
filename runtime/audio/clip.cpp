#include "audio/clip.h"

#include <sndfile.h>
#include <stb/stb_vorbis.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>

#include "core/file_util.h"

namespace tumble::audio {

namespace {

/// libsndfile's virtual I/O over a byte vector (reads) or a growing one (writes).
struct MemoryFile {
  std::vector<std::uint8_t>* bytes;
  sf_count_t pos = 0;
};

sf_count_t vioLength(void* user) { return sf_count_t(static_cast<MemoryFile*>(user)->bytes->size()); }
sf_count_t vioSeek(sf_count_t offset, int whence, void* user) {
  auto* f = static_cast<MemoryFile*>(user);
  const sf_count_t size = sf_count_t(f->bytes->size());
  sf_count_t to = whence == SEEK_SET ? offset : whence == SEEK_CUR ? f->pos + offset : size + offset;
  f->pos = std::clamp<sf_count_t>(to, 0, size);
  return f->pos;
}
sf_count_t vioRead(void* ptr, sf_count_t count, void* user) {
  auto* f = static_cast<MemoryFile*>(user);
  const sf_count_t n = std::max<sf_count_t>(0, std::min(count, sf_count_t(f->bytes->size()) - f->pos));
  if (n > 0) std::memcpy(ptr, f->bytes->data() + f->pos, std::size_t(n));
  f->pos += n;
  return n;
}
sf_count_t vioWrite(const void* ptr, sf_count_t count, void* user) {
  auto* f = static_cast<MemoryFile*>(user);
  if (sf_count_t(f->bytes->size()) < f->pos + count) f->bytes->resize(std::size_t(f->pos + count));
  std::memcpy(f->bytes->data() + f->pos, ptr, std::size_t(count));
  f->pos += count;
  return count;
}
sf_count_t vioTell(void* user) { return static_cast<MemoryFile*>(user)->pos; }

SF_VIRTUAL_IO kVirtualIo{vioLength, vioSeek, vioRead, vioWrite, vioTell};

struct SndFileCloser {
  void operator()(SNDFILE* f) const { sf_close(f); }
};

Clip mixDown(const float* interleaved, std::size_t frames, int channels, int rate_hz) {
  Clip clip;
  clip.rate_hz = rate_hz;
  clip.samples.resize(frames);
  for (std::size_t i = 0; i < frames; ++i) {
    double sum = 0;
    for (int c = 0; c < channels; ++c) sum += interleaved[i * std::size_t(channels) + std::size_t(c)];
    const double v = std::clamp(sum / channels, -1.0, 1.0);
    clip.samples[i] = std::int16_t(std::lround(v * 32767.0));
  }
  return clip;
}

Result<Clip> decodeWav(const std::vector<std::uint8_t>& bytes, const std::string& name) {
  std::vector<std::uint8_t> copy = bytes;  // libsndfile's virtual I/O wants a mutable user pointer
  MemoryFile mem{&copy};
  SF_INFO info{};
  std::unique_ptr<SNDFILE, SndFileCloser> f(sf_open_virtual(&kVirtualIo, SFM_READ, &info, &mem));
  if (!f) return makeError(name + ": not a readable WAV file (" + sf_strerror(nullptr) + ")");
  if ((info.format & SF_FORMAT_TYPEMASK) != SF_FORMAT_WAV && (info.format & SF_FORMAT_TYPEMASK) != SF_FORMAT_WAVEX)
    return makeError(name + ": starts like a WAV file but libsndfile reads another format");
  if (info.channels < 1 || info.channels > 8 || info.samplerate < 8000 || info.samplerate > 192000)
    return makeError(name + ": " + std::to_string(info.channels) + " channels at " + std::to_string(info.samplerate) +
                     " Hz; expected 1..8 channels at 8000..192000 Hz");
  if (info.frames <= 0) return makeError(name + ": holds no samples");
  if (double(info.frames) / info.samplerate > kMaxClipSeconds)
    return makeError(name + ": longer than " + std::to_string(int(kMaxClipSeconds)) + " s");
  std::vector<float> data(std::size_t(info.frames) * std::size_t(info.channels));
  const sf_count_t got = sf_readf_float(f.get(), data.data(), info.frames);
  if (got <= 0) return makeError(name + ": its sample data cannot be read (truncated or corrupt)");
  return mixDown(data.data(), std::size_t(got), info.channels, info.samplerate);
}

Result<Clip> decodeOgg(const std::vector<std::uint8_t>& bytes, const std::string& name) {
  if (bytes.size() > std::size_t(INT32_MAX)) return makeError(name + ": too large");
  int channels = 0, rate = 0;
  short* data = nullptr;
  const int frames = stb_vorbis_decode_memory(bytes.data(), int(bytes.size()), &channels, &rate, &data);
  std::unique_ptr<short, decltype(&std::free)> owned(data, &std::free);
  if (frames <= 0 || !data || channels < 1)
    return makeError(name + ": not a readable Ogg Vorbis file (truncated, corrupt, or Ogg holding another codec)");
  if (rate < 8000 || rate > 192000) return makeError(name + ": sample rate " + std::to_string(rate) + " Hz; expected 8000..192000");
  if (double(frames) / rate > kMaxClipSeconds)
    return makeError(name + ": longer than " + std::to_string(int(kMaxClipSeconds)) + " s");
  std::vector<float> f(std::size_t(frames) * std::size_t(channels));
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = float(data[i]) / 32768.0f;
  return mixDown(f.data(), std::size_t(frames), channels, rate);
}

}  // namespace

Result<Clip> decodeClip(const std::vector<std::uint8_t>& bytes, const std::string& name) {
  auto startsWith = [&](const char* magic) {
    const std::size_t n = std::strlen(magic);
    return bytes.size() >= n && std::memcmp(bytes.data(), magic, n) == 0;
  };
  if (startsWith("RIFF") || startsWith("RIFX") || startsWith("RF64")) return decodeWav(bytes, name);
  if (startsWith("OggS")) return decodeOgg(bytes, name);
  return makeError(name + ": not a sound file Tumble reads; expected a WAV (RIFF) or an Ogg Vorbis (.ogg) file");
}

Result<Clip> loadClip(const std::string& path) {
  auto bytes = readBinaryFile(path, kMaxSoundFileBytes);
  if (!bytes) return makeError(bytes.error());
  return decodeClip(*bytes, path);
}

Clip clipFromFloat(const std::vector<float>& mono, int rate_hz) { return mixDown(mono.data(), mono.size(), 1, rate_hz); }

Status writeWav(const std::string& path, const std::vector<float>& interleaved, int channels, int rate_hz) {
  std::vector<std::uint8_t> bytes;
  MemoryFile mem{&bytes};
  SF_INFO info{};
  info.channels = channels;
  info.samplerate = rate_hz;
  info.format = SF_FORMAT_WAV | SF_FORMAT_PCM_16;
  {
    std::unique_ptr<SNDFILE, SndFileCloser> f(sf_open_virtual(&kVirtualIo, SFM_WRITE, &info, &mem));
    if (!f) return makeError(path + ": cannot encode WAV (" + std::string(sf_strerror(nullptr)) + ")");
    sf_command(f.get(), SFC_SET_CLIPPING, nullptr, SF_TRUE);
    const sf_count_t frames = sf_count_t(interleaved.size() / std::size_t(channels));
    if (sf_writef_float(f.get(), interleaved.data(), frames) != frames) return makeError(path + ": WAV encoding failed");
  }
  return writeFileAtomic(path, bytes.data(), bytes.size());
}

}  // namespace tumble::audio
