#pragma once
// An audio system rendering offline (OpenAL Soft's loopback device), stepped
// like the game steps it, for the audio tests.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>

#include "audio/audio_system.h"

namespace tumble::audio::test {

constexpr double kTestStep_s = 1.0 / 60.0;

inline std::unique_ptr<AudioSystem> loopbackSystem() {
  auto sys = AudioSystem::create(AudioOutput::Loopback);
  EXPECT_TRUE(sys) << sys.error();
  return sys ? std::move(*sys) : nullptr;
}

/// Steps `seconds` of 1/60 s, calling `each` (if any) before every update.
inline void runFor(AudioSystem& sys, double seconds, const std::function<void()>& each = {}) {
  for (int i = 0; i < int(std::lround(seconds / kTestStep_s)); ++i) {
    if (each) each();
    sys.update(kTestStep_s);
  }
}

}  // namespace tumble::audio::test
