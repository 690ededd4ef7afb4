#pragma once
// Text on the pages motus writes beside its plots (the compare report and its replay, the stress
// and work–precision pages): what a scene's author wrote goes into HTML as text, never as markup.
#include <string>
#include <string_view>

namespace motus::plot {

// <, >, & and " as entities; everything else as it is (UTF-8 passes through).
std::string html_escape(std::string_view text);

// How every page starts, up to and including its <title>: the page's language (for a screen reader's
// voice and hyphenation) and a viewport, so that a phone shows the page at its own width rather than
// as a zoomed-out desktop page.
inline constexpr std::string_view kPageStart =
    "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
    "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"><title>";

}  // namespace motus::plot
