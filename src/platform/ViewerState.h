#pragma once
// What a viewer shows, as one value: the view, the AO parameters and the camera. The web page keeps it in its URL
// (so a view can be shared) and obscura-view accepts the same text with --state, e.g.
//   view=split&radius=2&samples=16&eye=3.2,2.6,6.2&target=-0.4,0.8,-1.6&up=0,1,0&fovy=55&near=0.1&far=40
// Keys: view (final | ao | ao-raw | normals | depth | split), every AoSettings parameter by its name, and the
// camera (eye, target, up as x,y,z; fovy in degrees; near; far). The camera's size follows the window or canvas.
#include <string>
#include <vector>

#include "core/AoSettings.h"
#include "core/Renderer.h"
#include "scene/Camera.h"

namespace obscura {

struct ViewerState {
  View view = View::Final;
  bool split = false;  // the final image with AO off left of the middle and on right of it
  AoSettings settings;
  Camera camera;

  // The view names a viewer offers, in order: the Renderer's views, then "split".
  static const std::vector<std::string>& viewModes();
  std::string viewMode() const;
  void setViewMode(const std::string& name);  // throws InputError

  // The state as query-string text (no leading '?'). Parameters equal to their defaults are left out; the view and
  // the camera are always written.
  std::string toQuery() const;
  // Applies query-string text (with or without a leading '?', '+' and %XX decoded) onto this state. Keys may come in
  // any order; parameters apply in the order of the parameter table, so "samples" precedes "turns". Throws
  // InputError naming the key on anything unknown or invalid, leaving the state unchanged. Returns whether the text
  // set the camera (any camera key).
  bool applyQuery(const std::string& query);
};

}  // namespace obscura
