#pragma once
// Sound files: decoding WAV (libsndfile) and Ogg Vorbis (stb_vorbis) into
// mono 16-bit clips, and writing a rendered stereo WAV (libsndfile, into
// memory, then written atomically).
#include <cstdint>
#include <string>
#include <vector>

#include "core/result.h"

namespace tumble::audio {

/// Largest sound file read, bytes (a 5-minute 48 kHz stereo 16-bit WAV is 55 MB).
constexpr std::size_t kMaxSoundFileBytes = std::size_t(64) << 20;
/// Longest decoded clip, s: a longer file is refused rather than eating memory.
constexpr double kMaxClipSeconds = 600;

/// Decoded sound: mono (several channels are averaged, since OpenAL places
/// only mono sources in space), 16-bit.
struct Clip {
  int rate_hz = 0;
  std::vector<std::int16_t> samples;
  double seconds() const { return rate_hz > 0 ? double(samples.size()) / rate_hz : 0; }
};

/// WAV (any PCM or float encoding libsndfile reads) or Ogg Vorbis, told
/// apart by their first bytes. `name` is the file, for messages; an
/// unknown, truncated or corrupt file is an error saying which and what
/// would be valid.
Result<Clip> decodeClip(const std::vector<std::uint8_t>& bytes, const std::string& name);
/// readBinaryFile (bounded) then decodeClip.
Result<Clip> loadClip(const std::string& path);
/// Float samples in [-1, 1] (clamped) to a clip.
Clip clipFromFloat(const std::vector<float>& mono, int rate_hz);

/// Interleaved float frames (channels per frame) as a 16-bit PCM WAV file, atomically.
Status writeWav(const std::string& path, const std::vector<float>& interleaved, int channels, int rate_hz);

}  // namespace tumble::audio
