// param_widgets.h: ImGui widgets generated from parameter declarations (lucent/params.h), the same
// declarations that drive the scene parser and `lucent render --help`: name, unit, range, choices, doc.
#pragma once
#include <string>
#include <string_view>

#include "lucent/params.h"

namespace lucent::viewer {

// "name [unit]" as the widget label.
std::string param_label(const ParamDecl& decl);
// One widget for `decl` editing values[decl.name]; the doc, range and unit show as a tooltip. True when the
// user changed the value this frame (Int and Float values stay within [min, max]).
bool param_widget(const ParamDecl& decl, ParamValues& values);
// Every declaration of the section, in declaration order. True when any changed.
bool param_section_widgets(const ParamSection& section, ParamValues& values);

// The declaration `name` in a section of scene_param_sections() ("objects[].material", "lights[]", ...), for
// labelling widgets that edit Scene fields directly; nullptr when absent.
const ParamDecl* find_scene_param(std::string_view section, std::string_view name);
// Float widgets for a scene field, ranged and labelled by its declaration (when found).
bool scene_float(std::string_view section, std::string_view name, float& value, float speed = 0.01f);
bool scene_vec3(std::string_view section, std::string_view name, glm::vec3& value, float speed = 0.01f);

}  // namespace lucent::viewer
