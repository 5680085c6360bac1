#pragma once
// What a viewer shows, as one value: the view, the frame's parameters, the timeline and the camera. The web page keeps
// it in its URL (so a view can be shared) and obscura-view accepts the same text with --state, e.g.
//   view=split&ao.radius=2&time=1.25&eye=3.2,2.6,6.2&target=-0.4,0.8,-1.6&up=0,1,0&fovy=55&near=0.1&far=40
// Keys: view (frameViewNames(): final, split, and every target's debug view), compare (the switch the split view
// compares: splitSwitches(); written when not "ao"), every parameter of RenderSettings by
// its name or alias ("radius" for "ao.radius": older links keep working), the timeline (animation: a name, an index,
// all or none; time in seconds; speed; play and loop: on or off; Timeline.h) and the camera (eye, target, up as
// x,y,z; fovy in degrees; near; far; projection=orthographic with ymag, the half height in metres, for an orthographic
// free camera; camera=NAME or INDEX when the view looks through one of the scene's own cameras instead: the name of
// its node or camera, or its index among them). The camera's size follows the window or canvas. The AO radius is in the
// scene's units; each scene loaded gets its own default radius unless a state text gave one (sceneLoaded), and
// starts at time 0 of its first animation.
#include <string>
#include <vector>

#include "platform/Timeline.h"
#include "renderer/RenderSettings.h"
#include "renderer/Renderer.h"
#include "scene/Camera.h"

namespace obscura {

struct ViewerState {
  View view = View::Final;
  RenderSettings settings;
  // The parameters' defaults in this viewer: the table's, except where the front end chose its own (setDefault: the
  // page turns dynamic resolution on). toQuery leaves out what equals them.
  RenderSettings defaults;
  Timeline timeline;
  Camera camera;  // the free camera, which orbits
  // The shown scene's own cameras (Scene::cameras) and the one the view looks through: -1 the free camera, else an
  // index into them (FrameOptions::sceneCamera). A scene loaded starts on the free camera.
  std::vector<SceneCamera> sceneCameras;
  int sceneCamera = -1;
  // "free", or the scene camera as state text names it (sceneCameraKey: its name, else its index).
  std::string cameraChoice() const;
  // "free", or one of sceneCameras by name or index; throws InputError listing them.
  void setCameraChoice(const std::string& text);

  // The AO radius of the scene shown when nobody sets one (scene/SceneScale.h: defaultAoRadius; the built-in scene:
  // 1). toQuery leaves ao.radius out at this value, so a URL holds a radius only once someone chose one.
  float defaultRadius = 1.0f;
  // Whether a state text (applyQuery: the page's URL, obscura-view's --state, the JS API's setState) gave the radius.
  // Such a radius is kept when another scene is loaded; otherwise each scene loaded starts at its own default
  // radius, whatever the keys or the controls had set for the previous one (sceneLoaded).
  bool radiusGiven = false;
  // A scene whose default AO radius is `radius` is now shown: records it, and sets ao.radius to it unless
  // radiusGiven.
  void sceneLoaded(float radius);

  // Makes `value` the default of parameter `name` here, and its value now (throws InputError as RenderSettings::set).
  void setDefault(const std::string& name, const std::string& value);

  // The view names a viewer offers, in order (the Renderer's: frameViewNames()).
  static const std::vector<std::string>& viewModes();
  std::string viewMode() const { return view.name; }
  void setViewMode(const std::string& name);  // throws InputError (the compared switch is kept)

  // The state as query-string text (no leading '?'), parameters by their full names. Parameters equal to their
  // defaults (or to their preset's values; the radius: to defaultRadius, unless radiusGiven) and the timeline's keys
  // at their defaults (Timeline::writeQuery) are left out; the view and the camera are always written.
  std::string toQuery() const;
  // Applies query-string text (with or without a leading '?', '+' and %XX decoded) onto this state. Keys may come in
  // any order; parameters apply in the order of the parameter table ("preset" first, then each effect's, so
  // "ao.samples" precedes "ao.turns"), the timeline's in Timeline::queryKeys()' order. Throws InputError naming the
  // key on anything unknown or invalid (or a parameter given twice, by name and alias), leaving the state unchanged.
  // Returns whether the text set the camera (any camera key). A radius in the text (ao.radius or radius) sets
  // radiusGiven.
  bool applyQuery(const std::string& query);
};

}  // namespace obscura
