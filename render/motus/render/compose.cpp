#include "motus/render/compose.hpp"

#include <algorithm>
#include <cmath>

#include "motus/render/text.hpp"

namespace motus::render {

Image contact_sheet(const std::vector<Image>& images, int columns, const std::vector<std::string>& labels,
                    const ComposeStyle& style) {
  if (images.empty()) return Image(1, 1, style.background);
  columns = std::clamp(columns, 1, static_cast<int>(images.size()));
  const int rows = (static_cast<int>(images.size()) + columns - 1) / columns;
  int cell_w = 0, cell_h = 0;
  for (const auto& im : images) cell_w = std::max(cell_w, im.width), cell_h = std::max(cell_h, im.height);
  const int band = style.label_size > 0 ? static_cast<int>(std::ceil(style.label_size * 1.7)) : 0;
  const int g = style.gap;
  Image sheet(columns * cell_w + (columns + 1) * g, rows * (cell_h + band) + (rows + 1) * g, style.background);
  for (size_t i = 0; i < images.size(); ++i) {
    const int c = static_cast<int>(i) % columns, r = static_cast<int>(i) / columns;
    const int x = g + c * (cell_w + g), y = g + r * (cell_h + band + g);
    if (band && i < labels.size())
      draw_text(sheet, x + cell_w / 2, y + static_cast<int>(band * 0.72), labels[i],
                {style.label_size, style.label_color, Align::center});
    sheet.paste(images[i], x + (cell_w - images[i].width) / 2, y + band);
  }
  return sheet;
}

Image compose_side_by_side(const std::vector<Image>& images, const std::vector<std::string>& labels,
                           const ComposeStyle& style) {
  return contact_sheet(images, static_cast<int>(images.size()), labels, style);
}

}  // namespace motus::render
