#pragma once
// The audio step (app/fixed_step.cpp calls it after the particles): what the
// scene's systems sound like this step, then the audio clock advances (the
// loopback output renders the step's frames). Also the listener from the
// render camera (play).
#include "app/scene.h"
#include "render/renderer.h"

namespace tumble::app {

/// Vehicles' engines, tyres (by the terrain's sound layer) and wind,
/// impacts from the step's new contacts, thunder for the storm's lightning
/// flashes in [start_s, start_s + dt_s) (render::lightningStrikes, what the
/// renderer draws), script sounds moved with their bodies. Makes the audio system on the first step that has something to
/// sound (a vehicle or a contact) unless the output is Silent; nothing at
/// all without one.
void stepAudio(Scene& scene, double start_s, double dt_s);

/// The listener at the camera's eye, looking where it looks.
Scene::Listener listenerAtCamera(const render::Camera& camera);

}  // namespace tumble::app
