#include "render/surface.hpp"

#include <algorithm>
#include <cmath>

namespace render {

PixelBox clip_box(const Rect& box) {
    const int x0 = int(std::lround(box.x)), y0 = int(std::lround(box.y));
    const int x1 = int(std::lround(box.right())), y1 = int(std::lround(box.bottom()));
    return {x0, y0, std::max(x0, x1), std::max(y0, y1)};
}

}  // namespace render
