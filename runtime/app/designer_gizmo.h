#pragma once
// The designer's gizmo: handles drawn on the selected object that the
// player drags with the mouse, as in every level editor.
//
//   red arrow    move along world X        blue arrow   move along world Z
//   yellow ring  turn about the vertical   white post   scale (drag its top up or down)
//
// Objects stand on the ground (the document puts y on the terrain), so there
// is no vertical move. Everything here is geometry on rays from the eye
// (Renderer::viewRay), free of GL and of the designer's state, so it is
// tested headless (tests/app/designer_gizmo_test.cpp). A handle is picked
// when the pointer's ray passes within kGizmoPickTolerance_rad of it, as
// seen from the eye: the same few pixels however far the object is.
#include <optional>
#include <vector>

#include "app/design_document.h"
#include "core/math.h"
#include "render/renderer.h"

namespace tumble::app {

enum class GizmoHandle { None, MoveX, MoveZ, Rotate, Scale };
const char* gizmoHandleName(GizmoHandle handle);  ///< "none", "move_x", "move_z", "rotate", "scale"

/// A ray from the eye (Renderer::viewRay): origin m, unit direction.
struct ViewRay {
  Eigen::Vector3f origin_m = Eigen::Vector3f::Zero();
  Eigen::Vector3f direction = Eigen::Vector3f::UnitZ();
};

/// Where the gizmo is drawn: its centre (the object's ground point, lifted a
/// little) and its arm length, which grows with the distance from the eye so
/// the handles keep their size on screen.
struct GizmoFrame {
  Eigen::Vector3f centre_m = Eigen::Vector3f::Zero();
  float arm_m = 2.0f;
};

inline constexpr float kGizmoPickTolerance_rad = 0.03f;  // about 12 px at 720 px and a 1 rad field of view
inline constexpr float kGizmoArmPerDistance = 0.15f;     // arm length / distance from the eye
inline constexpr float kGizmoMinArm_m = 1.0f, kGizmoMaxArm_m = 80.0f;
inline constexpr float kGizmoRingRadius = 0.7f;          // ring radius / arm length
inline constexpr float kGizmoMinScale = 0.05f, kGizmoMaxScale = 20.0f;  // one drag's scale factor limits

GizmoFrame gizmoFrameFor(const PlacedObject& object, const Eigen::Vector3f& eye_m);

/// The handle the ray points at (None: none within the tolerance); the
/// nearest to the ray's direction wins.
GizmoHandle pickGizmoHandle(const GizmoFrame& frame, const ViewRay& ray);

/// One drag: what was pressed, and the object and pointer where it started.
/// The frame is kept from the press, so the handles do not grow or move
/// under the pointer while it drags.
struct GizmoDrag {
  GizmoHandle handle = GizmoHandle::None;
  GizmoFrame frame;
  PlacedObject start;
  float startValue = 0;  ///< move: the axis parameter, m; rotate: the heading, rad; scale: the height, m
};

/// Starts a drag of `handle` at the pointer's ray; nothing when the ray is
/// parallel to what the handle moves on (e.g. the ring seen edge-on).
std::optional<GizmoDrag> beginGizmoDrag(GizmoHandle handle, const GizmoFrame& frame, const PlacedObject& object,
                                        const ViewRay& ray);

/// The object as the drag leaves it with the pointer on this ray: moved by
/// the pointer's travel along the axis, turned by the angle it swept around
/// the centre, or scaled by the ratio of the post's new height to the old
/// (kGizmoMinScale..kGizmoMaxScale). Unchanged when the ray says nothing
/// (parallel to the axis or the ring's plane).
PlacedObject dragGizmo(const GizmoDrag& drag, const ViewRay& ray);

/// The handles as lines, the hovered (or dragged) one brighter.
void addGizmoLines(const GizmoFrame& frame, GizmoHandle highlighted, std::vector<render::DebugLine>& lines);

/// A point of each handle (window picking in tests and the report): the
/// arrows' middles, the ring's point between +X and +Z, the post's top.
Eigen::Vector3f gizmoHandlePoint(const GizmoFrame& frame, GizmoHandle handle);

}  // namespace tumble::app
