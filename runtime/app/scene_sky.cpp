#include "app/scene_sky.h"

namespace tumble::app {

render::SkySettings skySettingsOf(const script::EnvironmentRequest& r) {
  render::SkySettings s;
  if (r.timeOfDay_h) s.timeOfDay_h = float(*r.timeOfDay_h);
  if (r.sunDirection) s.sunDirection = r.sunDirection->cast<float>();
  if (r.fogDistance_m) s.fogDistance_m = float(*r.fogDistance_m);
  s.cloudCover = float(r.cloudCover);
  s.weather = r.weather == "storm"    ? render::Weather::Storm
              : r.weather == "cloudy" ? render::Weather::Cloudy
                                      : render::Weather::Clear;
  s.wind_mps = r.wind_mps.cast<float>();
  return s;
}

}  // namespace tumble::app
