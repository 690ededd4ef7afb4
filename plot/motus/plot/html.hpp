#pragma once
// Text on the pages motus writes beside its plots (the compare report and its replay, the stress
// and work–precision pages): what a scene's author wrote goes into HTML as text, never as markup.
#include <string>
#include <string_view>

namespace motus::plot {

// <, >, & and " as entities; everything else as it is (UTF-8 passes through).
std::string html_escape(std::string_view text);

}  // namespace motus::plot
