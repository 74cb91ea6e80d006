#include "render/bdpt_strategies.h"

#include <algorithm>

#include "image/image_io.h"

namespace pt {

int strategy_layer(int s, int t) {
    const int d = s + t - 2;
    return 1 + d * d + 5 * d + 2 * s;  // 2 * sum over d' < d of (d' + 2) layers before depth d
}

int strategy_layer_count(int depth) { return depth < 0 ? 0 : (depth + 1) * (depth + 6); }

void write_strategy_images(const std::vector<Image>& layers, int depth, const std::string& dir) {
    if (layers.empty() || depth < 0) return;
    const int w = layers[0].width(), h = layers[0].height();
    // The grid: a row per depth d, a column per s (t = d + 2 - s), weighted images.
    Image grid(w * (depth + 2), h * (depth + 1));
    for (int d = 0; d <= depth; ++d) {
        for (int s = 0; s <= d + 1; ++s) {
            const int t = d + 2 - s;
            const size_t layer = size_t(strategy_layer(s, t) - 1);  // layers[] starts at layer 1
            if (layer + 1 >= layers.size()) continue;
            const std::string name = dir + "/s" + std::to_string(s) + "_t" + std::to_string(t);
            for (int k = 0; k < 2; ++k) {
                const std::string path = name + (k == 0 ? "_weighted" : "_unweighted");
                write_pfm(layers[layer + size_t(k)], path + ".pfm");
                write_png(layers[layer + size_t(k)], path + ".png");
            }
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) grid.set(s * w + x, d * h + y, layers[layer].at(x, y));
        }
    }
    write_png(grid, dir + "/strategies.png");
}

}  // namespace pt
