// scene_sections.h: the panel's scene editors: camera, lights, materials (objects), method and render
// settings. Each draws its ImGui widgets for the session's edited scene and marks the session edited.
#pragma once
#include "viewer/viewer_session.h"

namespace lucent::viewer {

void camera_section(ViewerSession& session);
void lights_section(ViewerSession& session);
void materials_section(ViewerSession& session);
void method_section(ViewerSession& session);
void render_section(ViewerSession& session);

}  // namespace lucent::viewer
