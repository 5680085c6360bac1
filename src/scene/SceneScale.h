#pragma once
// The AO radius a scene gets when nobody sets one: the one rule every front end applies (obscura-render,
// obscura-reference, obscura-bench, obscura-view and the web page, through platform/Viewer).
//
// The radius r is a length in the scene's own units (the estimator measures every distance in units of r, so a scene
// and its radius scaled together give the same AO). A model authored in centimetres or millimetres therefore needs a
// radius in those units, and a fixed default (1) is a hundredth of a cylinder of 2CylinderEngine.glb, which is in
// centimetres: its AO is plain white. The rule:
//
//   r = 5 % of the diameter of the scene's bounding sphere, rounded to two significant figures,
//
// the bounding sphere being the one around the world-space box of every vertex (Bounds: centre of the box, radius
// half its diagonal), so the diameter is the box's diagonal. 5 % of the model's size is the scale at which the
// contact shadows between its parts (a bolt on a flange, a part on another) read, without the whole model darkening
// under one blob; the browser benchmark against three.js uses the same fraction (docs/benchmarks.md: 41.8 for
// 2CylinderEngine.glb in centimetres; this rule gives 42). Two significant figures make it read well in a title bar,
// a URL and a slider.
//
// The exception: a scene that carries the radius it was designed for (Scene::designedAoRadius) keeps it. Only the
// built-in scene does, 1 (metre): it is the scene the defaults and the fitted estimator parameters were designed on,
// and the rule would give it a radius of its own size instead. scaleScene (--scene-scale) scales that radius with the
// scene, and the rule reads the scaled bounds, so --scene-scale composes with both.
#include <string>

#include "scene/Scene.h"

namespace obscura {

// The fraction of the bounding sphere's diameter the rule takes.
constexpr float kDefaultAoRadiusFraction = 0.05f;
// What the rule clamps to: the range of the ao.radius parameter (effects/ao/AoSettings.cpp; a test checks they agree).
constexpr float kMinAoRadius = 1e-4f, kMaxAoRadius = 1e6f;

// The rule for bounds: 5 % of their diagonal (the bounding sphere's diameter), to two significant figures, within
// kMinAoRadius .. kMaxAoRadius. Empty or degenerate (zero-size) bounds give 1.
float suggestedAoRadius(const Bounds& bounds);

// The radius `scene` gets when nobody sets one: its designedAoRadius if it has one (the built-in scene: 1 m), else
// suggestedAoRadius(scene.worldBounds()).
float defaultAoRadius(const Scene& scene);

// Why defaultAoRadius(scene) is what it is, for a note to the user, e.g. "5 % of the scene's bounding-sphere
// diameter, 836.05" or "the radius the built-in scene was designed for".
std::string defaultAoRadiusReason(const Scene& scene);

// `value` rounded to two significant figures (41.8 -> 42, 0.418 -> 0.42, 1234 -> 1200); 0 and non-finite values
// are returned as they are.
float roundToTwoSignificantFigures(float value);

}  // namespace obscura
