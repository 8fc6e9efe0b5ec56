// Where each value of the one table of render settings (render_settings.hpp) lives in a render
// request: one binding per row. The request's defaults, its JSON, its checks and `nimbus render`'s
// flags all reach a setting's field through it, so a new setting is its row, its field and its
// line here (docs/architecture.md, "A render setting").
#pragma once
#include <string>

#include "nimbus/render/sky/render_request.hpp"

namespace nimbus::render {

// Whether the setting is a field of the request: every one but the viewer's clock speed, which
// is the view state's (view_state.hpp).
bool in_request(Setting id);

// The setting's value in the table's unit (degrees for the blur, whose field holds radians).
// Throws std::logic_error for a setting that is not in the request.
double setting_value(const RenderRequest& request, Setting id);

// Sets the field from a value in the table's unit, once check_setting(id, value, name) has passed:
// std::invalid_argument "<name>: must be in <range>, got <value>" otherwise, the field unchanged.
void set_setting_value(RenderRequest& request, Setting id, double value, const std::string& name);

// Every setting of the request at the table's defaults: a still's (`nimbus render`, Python) or
// the viewer's (a view state's, where the viewer trades error for speed).
enum class SettingDefaults { Still, View };
void set_setting_defaults(RenderRequest& request, SettingDefaults which);

// The setting whose view key is "<section>.<key>" ("renderer", "slices"), or Setting::Count.
Setting setting_at_view_key(const std::string& section, const std::string& key);

}  // namespace nimbus::render
