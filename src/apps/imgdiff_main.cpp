// imgdiff: compares an image with a reference (PNG decoded to linear, or
// PFM or EXR) and prints RMSE, relMSE, PSNR, mean absolute difference and the
// share of pixels over a threshold (image/metrics.h); writes a false-colour
// heat map; exits 0 or 1 against --max-relmse / --max-rmse.
//
//   imgdiff A B [--heatmap FILE.png] [--max-relmse X] [--max-rmse X] [--threshold T]
//   imgdiff --dir A/ B/ [--heatmap-dir DIR] [--max-relmse X] [--max-rmse X] [--threshold T]
//
// B (the second image or folder) is the reference. Exit codes (DESIGN.md):
// 0 every comparison within the limits, 1 some comparison over a limit or
// a file missing from one folder, 2 bad input (missing file, not an image,
// sizes differ, bad flags) with one message on stderr.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "apps/number_flags.h"
#include "apps/tool_main.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "image/colormap.h"
#include "image/image_io.h"
#include "image/metrics.h"

namespace fs = std::filesystem;

namespace pt {
namespace {

struct ImgdiffOptions {
    std::vector<std::string> paths;    ///< the two images or folders
    bool dir = false;                  ///< --dir: compare folders by file name
    std::string heatmap;               ///< --heatmap FILE.png
    std::string heatmap_dir;           ///< --heatmap-dir DIR (with --dir)
    std::optional<double> max_relmse;  ///< --max-relmse X
    std::optional<double> max_rmse;    ///< --max-rmse X
    double threshold = 0.01;           ///< --threshold T for the share of pixels over T
    bool help = false;
};

const char* kUsage =
    "usage: imgdiff A B [--heatmap FILE.png] [--max-relmse X] [--max-rmse X] [--threshold T]\n"
    "       imgdiff --dir A/ B/ [--heatmap-dir DIR] [--max-relmse X] [--max-rmse X] [--threshold "
    "T]\n"
    "Compares A with the reference B (PNG, decoded from sRGB to linear, or PFM or EXR).\n"
    "  --heatmap FILE.png    write the per-pixel relMSE as a viridis heat map (log scale 1e-4 .. "
    "1)\n"
    "  --heatmap-dir DIR     with --dir: one heat map per file, same names\n"
    "  --max-relmse X        exit 1 when relMSE > X\n"
    "  --max-rmse X          exit 1 when RMSE > X\n"
    "  --threshold T         a pixel is 'over' when a channel differs by more than T (linear) "
    "[0.01]\n"
    "  --dir                 compare the PNG, PFM and EXR files of two folders by file name\n"
    "relMSE = mean over pixels and channels of (A - B)^2 / (B^2 + 0.01).\n"
    "Exit codes: 0 within limits, 1 over a limit or a file missing, 2 bad input.\n";

ImgdiffOptions parse(const std::vector<std::string>& args) {
    ImgdiffOptions o;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        auto value = [&]() -> const std::string& {
            if (i + 1 >= args.size()) throw InputError(a + ": missing value");
            return args[++i];
        };
        if (a == "-h" || a == "--help") {
            o.help = true;
        } else if (a == "--dir") {
            o.dir = true;
        } else if (a == "--heatmap") {
            o.heatmap = value();
        } else if (a == "--heatmap-dir") {
            o.heatmap_dir = value();
        } else if (a == "--max-relmse") {
            o.max_relmse = parse_real_number(a, value(), 0);
        } else if (a == "--max-rmse") {
            o.max_rmse = parse_real_number(a, value(), 0);
        } else if (a == "--threshold") {
            o.threshold = parse_real_number(a, value(), 0);
        } else if (a.size() > 1 && a[0] == '-') {
            throw InputError("unknown flag '" + a + "' (imgdiff --help lists the flags)");
        } else {
            o.paths.push_back(a);
        }
    }
    if (o.help) return o;
    if (o.paths.size() != 2)
        throw InputError(std::string("expected two ") + (o.dir ? "folders" : "images") + ", got " +
                         std::to_string(o.paths.size()) + " (imgdiff --help)");
    if (o.dir && !o.heatmap.empty()) throw InputError("--heatmap: use --heatmap-dir with --dir");
    if (!o.dir && !o.heatmap_dir.empty()) throw InputError("--heatmap-dir needs --dir");
    return o;
}

Image read_checked(const std::string& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw InputError(path + ": no such file");
    if (fs::is_directory(path, ec))
        throw InputError(path + ": is a folder (use --dir to compare folders)");
    std::string ext = file_extension(path);
    if (ext != ".png" && ext != ".pfm" && ext != ".exr")
        throw InputError(path + ": not a PNG, PFM or EXR image (extension '" + ext + "')");
    return read_image(path);
}

/// The first limit the metrics exceed, as "relMSE 0.02 > 0.01", or "".
std::string over_limit(const ImageMetrics& m, const ImgdiffOptions& o) {
    char buf[128];
    if (o.max_relmse && !(m.relmse <= *o.max_relmse)) {
        std::snprintf(buf, sizeof buf, "relMSE %.4g > %.4g", m.relmse, *o.max_relmse);
        return buf;
    }
    if (o.max_rmse && !(m.rmse <= *o.max_rmse)) {
        std::snprintf(buf, sizeof buf, "RMSE %.4g > %.4g", m.rmse, *o.max_rmse);
        return buf;
    }
    return "";
}

std::string format_psnr(double psnr) {
    if (std::isinf(psnr)) return "inf dB";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f dB", psnr);
    return buf;
}

/// PNG holds display values (sRGB-encoded, clamped to [0, 1]); PFM holds
/// linear radiance, unclamped. Both are compared as linear values, but a
/// clamped PNG against an unclamped PFM differs wherever radiance exceeds 1.
void warn_if_kinds_differ(const std::string& a, const std::string& b) {
    auto kind = [](const std::string& path) {
        return file_extension(path) == ".png" ? "an sRGB PNG (clamped to [0, 1])" : "a linear PFM (unclamped)";
    };
    if (file_extension(a) == file_extension(b)) return;
    std::cerr << "imgdiff: warning: " << a << " is " << kind(a) << " but " << b << " is " << kind(b)
              << ": values above 1 differ by design; compare two PNGs or two PFMs (pathtracer --hdr "
                 "writes the PFM)\n";
}

int compare_pair(const ImgdiffOptions& o) {
    if (!o.heatmap.empty()) {
        if (file_extension(o.heatmap) != ".png")
            throw InputError("--heatmap: expected a .png file name");
        refuse_overwriting_input(o.heatmap, "--heatmap", o.paths);
        check_output_path(o.heatmap, "--heatmap");
    }
    Image a = read_checked(o.paths[0]);
    Image b = read_checked(o.paths[1]);
    warn_if_kinds_differ(o.paths[0], o.paths[1]);
    require_same_size(a, b, o.paths[0] + " and " + o.paths[1]);
    ImageMetrics m = compare_images(a, b, o.threshold);
    std::printf("imgdiff: %s against reference %s, %dx%d\n", o.paths[0].c_str(), o.paths[1].c_str(),
                a.width(), a.height());
    std::printf("  RMSE               %.6g\n", m.rmse);
    std::printf("  relMSE             %.6g\n", m.relmse);
    std::printf("  PSNR               %s\n", format_psnr(m.psnr).c_str());
    std::printf("  mean abs diff      %.6g\n", m.mean_abs_diff);
    std::printf("  pixels over %-6g %.3f%% (%zu of %zu)\n", m.threshold, 100.0 * m.share_over,
                m.pixels_over, a.pixel_count());
    if (!o.heatmap.empty()) {
        write_png(error_heatmap(a, b), o.heatmap);
        std::printf("  heat map           %s (per-pixel relMSE, viridis, log scale 1e-4 .. 1)\n",
                    o.heatmap.c_str());
    }
    std::string over = over_limit(m, o);
    if (!over.empty()) {
        std::printf("imgdiff: FAIL: %s\n", over.c_str());
        return kExitFailure;
    }
    if (o.max_relmse || o.max_rmse) std::printf("imgdiff: PASS\n");
    return kExitOk;
}

/// File names of the PNG, PFM and EXR images directly inside `dir`.
std::set<std::string> images_in(const std::string& dir) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) throw InputError(dir + ": no such folder");
    std::set<std::string> names;
    for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
        std::string ext = file_extension(e.path().string());
        if (e.is_regular_file() && (ext == ".png" || ext == ".pfm" || ext == ".exr"))
            names.insert(e.path().filename().string());
    }
    if (ec) throw InputError(dir + ": cannot list the folder: " + ec.message());
    return names;
}

int compare_dirs(const ImgdiffOptions& o) {
    const std::string& da = o.paths[0];
    const std::string& db = o.paths[1];
    std::set<std::string> a = images_in(da), b = images_in(db);
    std::set<std::string> all(a.begin(), a.end());
    all.insert(b.begin(), b.end());
    if (all.empty())
        throw InputError(da + " and " + db + ": no PNG, PFM or EXR images in either folder");
    if (!o.heatmap_dir.empty()) {
        std::error_code ec;
        fs::create_directories(o.heatmap_dir, ec);
        if (!fs::is_directory(o.heatmap_dir))
            throw InputError("--heatmap-dir: cannot create " + o.heatmap_dir);
        // Heat maps are named like the images: in an input folder they would replace them.
        refuse_overwriting_input(o.heatmap_dir, "--heatmap-dir", {da, db});
    }
    size_t width = 8;
    for (const std::string& n : all)
        width = std::max(width, n.size());
    std::printf("%-*s  %-9s  %-10s  %-10s  %-9s  %-8s  %s\n", int(width), "file", "size", "RMSE",
                "relMSE", "PSNR", "over", "result");
    int compared = 0, missing = 0, failed = 0, bad = 0;
    for (const std::string& name : all) {
        if (!a.count(name) || !b.count(name)) {
            std::printf("%-*s  %-9s  %-10s  %-10s  %-9s  %-8s  missing in %s\n", int(width),
                        name.c_str(), "-", "-", "-", "-", "-", (a.count(name) ? db : da).c_str());
            ++missing;
            continue;
        }
        try {
            Image x = read_checked((fs::path(da) / name).string());
            Image y = read_checked((fs::path(db) / name).string());
            require_same_size(x, y, name);
            ImageMetrics m = compare_images(x, y, o.threshold);
            if (!o.heatmap_dir.empty()) {
                std::string heatmap = (fs::path(o.heatmap_dir) / (fs::path(name).stem().string() + ".png")).string();
                write_png(error_heatmap(x, y), heatmap);
            }
            std::string over = over_limit(m, o);
            char size[32], share[32];
            std::snprintf(size, sizeof size, "%dx%d", x.width(), x.height());
            std::snprintf(share, sizeof share, "%.2f%%", 100.0 * m.share_over);
            std::printf("%-*s  %-9s  %-10.4g  %-10.4g  %-9s  %-8s  %s\n", int(width), name.c_str(),
                        size, m.rmse, m.relmse, format_psnr(m.psnr).c_str(), share,
                        over.empty() ? "ok" : ("FAIL: " + over).c_str());
            ++compared;
            if (!over.empty()) ++failed;
        } catch (const InputError& e) {
            std::printf("%-*s  error: %s\n", int(width), name.c_str(), e.what());
            ++bad;
        }
    }
    std::printf(
        "imgdiff: %d compared, %d over a limit, %d missing, %d unreadable or of different sizes\n",
        compared, failed, missing, bad);
    if (bad > 0) return kExitBadInput;
    return (failed > 0 || missing > 0) ? kExitFailure : kExitOk;
}

}  // namespace
}  // namespace pt

int main(int argc, char** argv) {
    return pt::run_tool("imgdiff", argc, argv, [](const std::vector<std::string>& args) {
        pt::ImgdiffOptions o = pt::parse(args);
        if (o.help) {
            std::cout << pt::kUsage;
            return int(pt::kExitOk);
        }
        return o.dir ? pt::compare_dirs(o) : pt::compare_pair(o);
    });
}
