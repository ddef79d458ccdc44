#pragma once
// atlas-view's one page, HTML with its script and style inline (tools/view/atlas_view.html,
// embedded at build time): it draws what /events sends (view_json.h).

#include <string_view>

namespace atlas::view {

std::string_view ViewPage();

}  // namespace atlas::view
