// tessera-accuracy: what each accuracy knob costs in time and buys in error, for one scene.
//   tessera-accuracy SCENE.sdl -o DIR [--width W] [--height H] [--repeats N] [--threads T]
//                    [--seed S] [--shadows none|hard|soft]
// Writes DIR/report.md with its plots; see docs/ACCURACY.md.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <optional>
#include <string>

#include "bench/accuracy/accuracy_report.h"
#include "bench/accuracy/report_writer.h"
#include "common/loaders/sdl_loader.h"
#include "common/scene/source_location.h"

namespace {

constexpr const char* kUsage =
    "usage: tessera-accuracy SCENE.sdl -o DIR [--width W] [--height H] [--repeats N] "
    "[--threads T] [--seed S] [--shadows none|hard|soft]\n";

int number(const std::string& flag, const std::string& text, int lo, int hi) {
  std::size_t used = 0;
  int v = 0;
  try {
    v = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || v < lo || v > hi)
    throw std::invalid_argument(flag + " takes a whole number in [" + std::to_string(lo) + ", " +
                                std::to_string(hi) + "], not '" + text + "'");
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace tessera;
  try {
    std::string scene_path, dir;
    AccuracyOptions options;
    options.base.width = 160;
    options.base.height = 120;
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      const auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
        return argv[++i];
      };
      if (arg == "-o")
        dir = value();
      else if (arg == "--width")
        options.base.width = number(arg, value(), 1, 4096);
      else if (arg == "--height")
        options.base.height = number(arg, value(), 1, 4096);
      else if (arg == "--repeats")
        options.repeats = number(arg, value(), 1, 101);
      else if (arg == "--threads")
        options.threads = number(arg, value(), 0, 1024);
      else if (arg == "--seed")
        options.base.seed = static_cast<unsigned>(number(arg, value(), 0, 1 << 30));
      else if (arg == "--shadows") {
        const std::string name = value();
        const std::optional<ShadowMode> mode = parse_shadow_mode(name);
        if (!mode)
          throw std::invalid_argument("--shadows takes none, hard or soft, not '" + name + "'");
        options.base.shadows = *mode;
      } else if (arg == "--help" || arg == "-h") {
        std::fputs(kUsage, stdout);
        return 0;
      } else if (!arg.empty() && arg[0] == '-')
        throw std::invalid_argument("unknown option " + arg);
      else if (scene_path.empty())
        scene_path = arg;
      else
        throw std::invalid_argument("one scene only, got '" + arg + "' too");
    }
    if (scene_path.empty() || dir.empty())
      throw std::invalid_argument("needs SCENE.sdl and -o DIR");
    options.progress = [](const std::string& line) {
      std::fprintf(stderr, "  %s\n", line.c_str());
    };
    const Scene scene = load_sdl_file(scene_path);
    const AccuracyReport report =
        measure_accuracy(scene, std::filesystem::path(scene_path).filename().string(), options);
    for (const std::string& path : write_accuracy_report(report, dir))
      std::printf("wrote %s\n", path.c_str());
    return 0;
  } catch (const SceneError& e) {
    std::fprintf(stderr, "%s\n", e.what());
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "tessera-accuracy: %s\n%s", e.what(), kUsage);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tessera-accuracy: %s\n", e.what());
  }
  return 1;
}
