#pragma once
// The scenario's environment.set request (script) as the renderer's sky
// settings (render/sky.h): the one place that knows both.
#include "render/sky.h"
#include "script/environment_request.h"

namespace tumble::app {

render::SkySettings skySettingsOf(const script::EnvironmentRequest& request);

}  // namespace tumble::app
