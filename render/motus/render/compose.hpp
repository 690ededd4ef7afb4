#pragma once
// Putting images together: labelled panels side by side (one engine per panel: motus |
// Box2D | Bullet) and contact sheets (a grid of frames).
#include <string>
#include <vector>

#include "motus/render/image.hpp"

namespace motus::render {

struct ComposeStyle {
  Color background{255, 255, 255, 255};
  Color label_color{40, 44, 52, 255};
  double label_size = 15;  // pixels; 0: no label band
  int gap = 4;             // pixels between panels
};

// The images in a row, each under its label (labels may be fewer than images).
Image compose_side_by_side(const std::vector<Image>& images, const std::vector<std::string>& labels = {},
                           const ComposeStyle& style = {});

// The images in a grid of `columns`, each under its label, row by row.
Image contact_sheet(const std::vector<Image>& images, int columns, const std::vector<std::string>& labels = {},
                    const ComposeStyle& style = {});

}  // namespace motus::render
