#pragma once
// What a viewer shows, as one value: the view, the frame's parameters and the camera. The web page keeps it in its
// URL (so a view can be shared) and obscura-view accepts the same text with --state, e.g.
//   view=split&ao.radius=2&ao.samples=16&eye=3.2,2.6,6.2&target=-0.4,0.8,-1.6&up=0,1,0&fovy=55&near=0.1&far=40
// Keys: view (frameViewNames(): final, split, and every target's debug view), every parameter of RenderSettings by
// its name or alias ("radius" for "ao.radius": older links keep working), and the camera (eye, target, up as x,y,z;
// fovy in degrees; near; far). The camera's size follows the window or canvas.
#include <string>
#include <vector>

#include "core/RenderSettings.h"
#include "core/Renderer.h"
#include "scene/Camera.h"

namespace obscura {

struct ViewerState {
  View view = View::Final;
  RenderSettings settings;
  Camera camera;

  // The view names a viewer offers, in order (the Renderer's: frameViewNames()).
  static const std::vector<std::string>& viewModes();
  std::string viewMode() const { return view.name; }
  void setViewMode(const std::string& name);  // throws InputError

  // The state as query-string text (no leading '?'), parameters by their full names. Parameters equal to their
  // defaults (or to their preset's values) are left out; the view and the camera are always written.
  std::string toQuery() const;
  // Applies query-string text (with or without a leading '?', '+' and %XX decoded) onto this state. Keys may come in
  // any order; parameters apply in the order of the parameter table ("preset" first, then each effect's, so
  // "ao.samples" precedes "ao.turns"). Throws InputError naming the key on anything unknown or invalid (or a
  // parameter given twice, by name and alias), leaving the state unchanged. Returns whether the text set the camera
  // (any camera key).
  bool applyQuery(const std::string& query);
};

}  // namespace obscura
