#include "core/cli_finite.h"
#include "tools/terrain/terrain_commands.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/terrain_scene.h"
#include "terrain/filters.h"
#include "terrain/generators.h"
#include "terrain/height_map.h"
#include "terrain/terrain.h"
#include "terrain/terrain_desc.h"

namespace tumble::tools {

namespace {

using namespace tumble::terrain;

struct Loaded {
  HeightMap map;
  TerrainDesc desc;
  bool hasSidecar = false;
};

Result<Loaded> loadInput(const std::string& path) {
  auto map = loadHeightMapPng(path);
  if (!map) return makeError(map.error());
  auto desc = loadSidecar(path);
  if (!desc) return makeError(desc.error());
  std::error_code ec;
  const bool hasSidecar = std::filesystem::exists(sidecarPath(path), ec);
  return Loaded{std::move(*map), *desc, hasSidecar};
}

// Writes the map, and the sidecar when the input had one.
Status writeOutput(const HeightMap& map, const TerrainDesc& desc, bool withSidecar, const std::string& path) {
  if (auto ok = saveHeightMapPng(map, path); !ok) return ok;
  if (withSidecar) return saveSidecar(path, desc);
  return Ok{};
}

// "a,b[,c...]" -> exactly `count` finite numbers.

Result<std::vector<double>> parseNumbers(const std::string& text, std::size_t count, const std::string& option) {
  std::vector<double> values;
  std::stringstream ss(text);
  std::string part;
  while (std::getline(ss, part, ',')) {
    char* end = nullptr;
    const double v = std::strtod(part.c_str(), &end);
    if (part.empty() || end == part.c_str() || *end != '\0' || !std::isfinite(v))
      return makeError(option + ": \"" + part + "\" is not a number (expected " + std::to_string(count) +
                       " comma-separated numbers)");
    values.push_back(v);
  }
  if (count != 0 && values.size() != count)
    return makeError(option + ": expected " + std::to_string(count) + " comma-separated numbers, got \"" + text + "\"");
  return values;
}

// Size from --size or --width/--height.
Result<std::pair<int, int>> pickSize(int size, int width, int height, const std::string& command) {
  if (size > 0) return std::pair{size, size};
  if (width > 0 && height > 0) return std::pair{width, height};
  return makeError(command + ": give --size N or both --width W and --height H");
}

// Run `body`, print its error, set exitCode.
template <typename Fn>
void runCommand(const std::string& name, int& exitCode, Fn&& body) {
  const Status status = body();
  if (status) {
    exitCode = 0;
  } else {
    std::cerr << "tumble terrain " << name << ": " << status.error() << "\n";
    exitCode = 1;
  }
}

void addGen(CLI::App& terrain, int& exitCode) {
  struct Opts {
    int size = 0, width = 0, height = 0;
    std::uint64_t seed = 1;
    double roughness = 0.5;
    std::string out;
  };
  auto o = std::make_shared<Opts>();
  auto* cmd = terrain.add_subcommand("gen", "Generate a plasma-fractal height map (16-bit PNG)");
  cmd->add_option("--size", o->size, "Square size in samples (2..4097; 2^n+1 avoids cropping)");
  cmd->add_option("--width", o->width, "Samples along X (with --height, instead of --size)");
  cmd->add_option("--height", o->height, "Samples along Z");
  cmd->add_option("--seed", o->seed, "Random seed; same seed, same bytes")->required();
  cmd->add_option("--roughness", o->roughness, "Amplitude kept per octave, (0, 1]; 0.5 natural, 0.7 craggy")
      ->check(CLI::Range(0.01, 1.0))->check(kFinite);
  cmd->add_option("--out", o->out, "Output PNG")->required();
  cmd->callback([o, &exitCode] {
    runCommand("gen", exitCode, [&]() -> Status {
      auto size = pickSize(o->size, o->width, o->height, "gen");
      if (!size) return makeError(size.error());
      if (auto ok = checkHeightMapSize(size->first, size->second, "gen"); !ok) return ok;
      const HeightMap map = generatePlasma(size->first, size->second, {o->seed, o->roughness});
      return saveHeightMapPng(map, o->out);
    });
  });
}

void addSmoothSharpen(CLI::App& terrain, int& exitCode) {
  struct Opts {
    std::string in, out;
    int passes = 1;
    double amount = 0.5;
  };
  auto s = std::make_shared<Opts>();
  auto* smoothCmd = terrain.add_subcommand("smooth", "Smooth with the 3x3 binomial kernel");
  smoothCmd->add_option("input", s->in, "Input height map PNG")->required();
  smoothCmd->add_option("--out", s->out, "Output PNG")->required();
  smoothCmd->add_option("--passes", s->passes, "How many times to apply the kernel")->check(CLI::Range(1, 1000));
  smoothCmd->callback([s, &exitCode] {
    runCommand("smooth", exitCode, [&]() -> Status {
      auto in = loadInput(s->in);
      if (!in) return makeError(in.error());
      return writeOutput(smooth(in->map, s->passes), in->desc, in->hasSidecar, s->out);
    });
  });

  auto h = std::make_shared<Opts>();
  auto* sharpenCmd = terrain.add_subcommand("sharpen", "Sharpen with a Laplacian kernel");
  sharpenCmd->add_option("input", h->in, "Input height map PNG")->required();
  sharpenCmd->add_option("--out", h->out, "Output PNG")->required();
  sharpenCmd->add_option("--amount", h->amount, "Strength, 0.5 moderate, 1 strong")->check(CLI::Range(0.0, 10.0))->check(kFinite);
  sharpenCmd->callback([h, &exitCode] {
    runCommand("sharpen", exitCode, [&]() -> Status {
      auto in = loadInput(h->in);
      if (!in) return makeError(in.error());
      return writeOutput(sharpen(in->map, h->amount), in->desc, in->hasSidecar, h->out);
    });
  });
}

void addConvolve(CLI::App& terrain, int& exitCode) {
  struct Opts {
    std::string in, out, kernel;
    bool normalize = false;
  };
  auto o = std::make_shared<Opts>();
  auto* cmd = terrain.add_subcommand("convolve", "Convolve with a custom square kernel");
  cmd->add_option("input", o->in, "Input height map PNG")->required();
  cmd->add_option("--kernel", o->kernel, "Row-major weights, comma-separated; 9, 25, 49... of them")->required();
  cmd->add_flag("--normalize", o->normalize, "Divide the weights by their sum");
  cmd->add_option("--out", o->out, "Output PNG")->required();
  cmd->callback([o, &exitCode] {
    runCommand("convolve", exitCode, [&]() -> Status {
      auto weights = parseNumbers(o->kernel, 0, "--kernel");
      if (!weights) return makeError(weights.error());
      const int size = int(std::lround(std::sqrt(double(weights->size()))));
      if (o->normalize) {
        double sum = 0;
        for (double w : *weights) sum += w;
        if (sum == 0) return makeError("--kernel: weights sum to 0, cannot --normalize");
        for (double& w : *weights) w /= sum;
      }
      auto kernel = makeKernel(size, std::move(*weights), "--kernel");
      if (!kernel) return makeError(kernel.error());
      auto in = loadInput(o->in);
      if (!in) return makeError(in.error());
      return writeOutput(convolve(in->map, *kernel), in->desc, in->hasSidecar, o->out);
    });
  });
}

void addResample(CLI::App& terrain, int& exitCode) {
  struct Opts {
    std::string in, out;
    int size = 0, width = 0, height = 0;
  };
  auto o = std::make_shared<Opts>();
  auto* cmd = terrain.add_subcommand("resample", "Bicubic resampling to a new size (corners stay put)");
  cmd->add_option("input", o->in, "Input height map PNG")->required();
  cmd->add_option("--size", o->size, "New square size in samples");
  cmd->add_option("--width", o->width, "New samples along X (with --height)");
  cmd->add_option("--height", o->height, "New samples along Z");
  cmd->add_option("--out", o->out, "Output PNG")->required();
  cmd->callback([o, &exitCode] {
    runCommand("resample", exitCode, [&]() -> Status {
      auto size = pickSize(o->size, o->width, o->height, "resample");
      if (!size) return makeError(size.error());
      if (auto ok = checkHeightMapSize(size->first, size->second, "resample"); !ok) return ok;
      auto in = loadInput(o->in);
      if (!in) return makeError(in.error());
      TerrainDesc desc = in->desc;
      const double ratioX = double(in->map.width() - 1) / double(size->first - 1);
      const double ratioZ = double(in->map.height() - 1) / double(size->second - 1);
      desc.spacing_m *= ratioX;
      if (in->hasSidecar && std::abs(ratioX - ratioZ) > 1e-9 * ratioX)
        std::cerr << "tumble terrain resample: note: X and Z are scaled differently; the sidecar keeps the X "
                     "spacing, so the Z extent changes\n";
      return writeOutput(resampleBicubic(in->map, size->first, size->second), desc, in->hasSidecar, o->out);
    });
  });
}

void addRidgeCmd(CLI::App& terrain, int& exitCode) {
  struct Opts {
    std::string in, out, from, to;
    double height_m = 20, width_m = 10, jaggedness = 0.2;
    std::uint64_t seed = 1;
    bool ditch = false;
  };
  auto o = std::make_shared<Opts>();
  auto* cmd = terrain.add_subcommand("ridge", "Add a ridge (or --ditch) along a midpoint-displaced line");
  cmd->add_option("input", o->in, "Input height map PNG")->required();
  cmd->add_option("--from", o->from, "Start X,Z in world metres")->required();
  cmd->add_option("--to", o->to, "End X,Z in world metres")->required();
  cmd->add_option("--height", o->height_m, "Crest height (or ditch depth) in metres, default 20")
      ->check(CLI::Range(0.0, 1e5))->check(kFinite);
  cmd->add_option("--width", o->width_m, "Half-width in metres from crest to foot, default 10")
      ->check(CLI::Range(0.001, 1e6))->check(kFinite);
  cmd->add_option("--jaggedness", o->jaggedness, "Sideways wander per segment length, 0 straight, default 0.2")
      ->check(CLI::Range(0.0, 1.0))->check(kFinite);
  cmd->add_option("--seed", o->seed, "Random seed for the wander");
  cmd->add_flag("--ditch", o->ditch, "Dig instead of raising");
  cmd->add_option("--out", o->out, "Output PNG")->required();
  cmd->callback([o, &exitCode] {
    runCommand("ridge", exitCode, [&]() -> Status {
      auto from = parseNumbers(o->from, 2, "--from");
      if (!from) return makeError(from.error());
      auto to = parseNumbers(o->to, 2, "--to");
      if (!to) return makeError(to.error());
      auto in = loadInput(o->in);
      if (!in) return makeError(in.error());
      const TerrainDesc& d = in->desc;
      RidgeParams p;
      p.fromX = ((*from)[0] - d.originX_m) / d.spacing_m;
      p.fromZ = ((*from)[1] - d.originZ_m) / d.spacing_m;
      p.toX = ((*to)[0] - d.originX_m) / d.spacing_m;
      p.toZ = ((*to)[1] - d.originZ_m) / d.spacing_m;
      p.height = (o->ditch ? -o->height_m : o->height_m) / d.heightScale_m;
      p.halfWidth = o->width_m / d.spacing_m;
      p.jaggedness = o->jaggedness;
      p.seed = o->seed;
      addRidge(in->map, p);
      return writeOutput(in->map, d, in->hasSidecar, o->out);
    });
  });
}

void addBump(CLI::App& terrain, int& exitCode) {
  struct Opts {
    std::string in, out, region;
    double amplitude_m = 20, roughness = 0.5;
    std::uint64_t seed = 1;
  };
  auto o = std::make_shared<Opts>();
  auto* cmd = terrain.add_subcommand("bump", "Add plasma to a region, fading to nothing at its border");
  cmd->add_option("input", o->in, "Input height map PNG")->required();
  cmd->add_option("--region", o->region, "X,Z,W,H in world metres (corner and size)")->required();
  cmd->add_option("--amplitude", o->amplitude_m, "Largest height added in metres (negative digs), default 20")->check(kFinite);
  cmd->add_option("--roughness", o->roughness, "Amplitude kept per octave, (0, 1]")->check(CLI::Range(0.01, 1.0))->check(kFinite);
  cmd->add_option("--seed", o->seed, "Random seed");
  cmd->add_option("--out", o->out, "Output PNG")->required();
  cmd->callback([o, &exitCode] {
    runCommand("bump", exitCode, [&]() -> Status {
      auto r = parseNumbers(o->region, 4, "--region");
      if (!r) return makeError(r.error());
      if ((*r)[2] <= 0 || (*r)[3] <= 0) return makeError("--region: width and height must be > 0 metres");
      auto in = loadInput(o->in);
      if (!in) return makeError(in.error());
      const TerrainDesc& d = in->desc;
      const int x0 = int(std::lround(((*r)[0] - d.originX_m) / d.spacing_m));
      const int z0 = int(std::lround(((*r)[1] - d.originZ_m) / d.spacing_m));
      const double w = std::min((*r)[2] / d.spacing_m + 1, double(2 * kMaxHeightMapSide));
      const double h = std::min((*r)[3] / d.spacing_m + 1, double(2 * kMaxHeightMapSide));
      addPlasmaRegion(in->map, x0, z0, int(std::lround(w)), int(std::lround(h)), o->amplitude_m / d.heightScale_m,
                      {o->seed, o->roughness});
      return writeOutput(in->map, d, in->hasSidecar, o->out);
    });
  });
}

void addImport(CLI::App& terrain, int& exitCode) {
  struct Opts {
    std::string in, out;
  };
  auto o = std::make_shared<Opts>();
  auto* cmd = terrain.add_subcommand("import", "Convert an image made elsewhere (8-bit grey or RGB) to a 16-bit map");
  cmd->add_option("input", o->in, "Input PNG")->required();
  cmd->add_option("--out", o->out, "Output 16-bit PNG")->required();
  cmd->callback([o, &exitCode] {
    runCommand("import", exitCode, [&]() -> Status {
      auto in = loadInput(o->in);
      if (!in) return makeError(in.error());
      return writeOutput(in->map, in->desc, in->hasSidecar, o->out);
    });
  });
}

void addPreview(CLI::App& terrain, int& exitCode) {
  struct Opts {
    std::string in, out;
    double azimuth_deg = 315, elevation_deg = 45;
    bool grey = false;
  };
  auto o = std::make_shared<Opts>();
  auto* cmd = terrain.add_subcommand("preview", "Write a shaded-relief RGB preview PNG");
  cmd->add_option("input", o->in, "Input height map PNG")->required();
  cmd->add_option("--out", o->out, "Output RGB PNG")->required();
  cmd->add_option("--azimuth", o->azimuth_deg,
                  "Light direction in degrees, clockwise from -Z seen from above (315 = from -X,-Z)")
      ->check(CLI::Range(-360.0, 360.0))->check(kFinite);
  cmd->add_option("--elevation", o->elevation_deg, "Light elevation above the horizon, degrees")
      ->check(CLI::Range(0.0, 90.0))->check(kFinite);
  cmd->add_flag("--grey", o->grey, "Grey shading without the elevation tint");
  cmd->callback([o, &exitCode] {
    runCommand("preview", exitCode, [&]() -> Status {
      auto in = loadInput(o->in);
      if (!in) return makeError(in.error());
      const double az = o->azimuth_deg * kPi / 180, el = o->elevation_deg * kPi / 180;
      ReliefParams p;
      // Azimuth 0 = light from -Z ("north"), 90 = from +X.
      p.towardLight = Vec3(Real(std::sin(az) * std::cos(el)), Real(std::sin(el)), Real(-std::cos(az) * std::cos(el)));
      p.elevationTint = !o->grey;
      return saveShadedReliefPng(in->map, in->desc, o->out, p);
    });
  });
}

void addInfo(CLI::App& terrain, int& exitCode) {
  struct Opts {
    std::string file;
    bool json = false;
  };
  auto o = std::make_shared<Opts>();
  auto* cmd = terrain.add_subcommand("info", "Load a height map as the runtime does and report its memory");
  cmd->add_option("file", o->file, "Height map PNG")->required();
  cmd->add_flag("--json", o->json, "Print one JSON object");
  cmd->callback([o, &exitCode] {
    runCommand("info", exitCode, [&]() -> Status {
      auto t = Terrain::loadPng(o->file);
      if (!t) return makeError(t.error());
      const TerrainMemory mem = t->memory();
      const auto& s = t->heights().samples();
      const auto [lo, hi] = std::minmax_element(s.begin(), s.end());
      const double samples = double(t->heights().sampleCount());
      nlohmann::json j = {{"width", t->heights().width()},
                          {"height", t->heights().height()},
                          {"bytes_heights", mem.heights},
                          {"bytes_tree", mem.tree},
                          {"bytes_per_sample", double(mem.heights + mem.tree) / samples},
                          {"tree_levels", t->tree().levelCount()},
                          {"tree_leaf_blocks", t->tree().leafBlocks()},
                          {"spacing_m", t->desc().spacing_m},
                          {"min_height_m", t->toHeight_m(*lo)},
                          {"max_height_m", t->toHeight_m(*hi)}};
      if (o->json) {
        std::cout << j.dump() << "\n";
      } else {
        std::printf("%s: %d x %d samples, %.3f m spacing, heights %.2f .. %.2f m\n", o->file.c_str(),
                    t->heights().width(), t->heights().height(), t->desc().spacing_m, t->toHeight_m(*lo),
                    t->toHeight_m(*hi));
        std::printf("memory: heights %zu bytes, tree %zu bytes (%d levels, %dx%d-block leaves), %.4f bytes/sample\n",
                    mem.heights, mem.tree, t->tree().levelCount(), t->tree().leafBlocks(), t->tree().leafBlocks(),
                    double(mem.heights + mem.tree) / samples);
        std::fflush(stdout);
      }
      return Ok{};
    });
  });
}

void addMaterials(CLI::App& terrain, int& exitCode) {
  struct Opts {
    std::string in;
    bool island = false;
    bool force = false;
    double spacing_m = 1, height_m = 40;  // the scene's defaults for a map without a sidecar
  };
  auto o = std::make_shared<Opts>();
  auto* cmd = terrain.add_subcommand(
      "materials", "Paint material layers from slope and height and write them beside the map "
                   "(NAME.texture.png, NAME.bump.png, NAME.friction.png, NAME.sound.png) for editing");
  cmd->add_option("input", o->in, "Height map PNG")->required();
  cmd->add_flag("--island", o->island, "Paint sand at the shore, as the island style does");
  cmd->add_flag("--force", o->force, "Overwrite layer files that already exist");
  cmd->add_option("--spacing", o->spacing_m, "Metres between samples without a sidecar (as terrain.spacing)")
      ->check(CLI::Range(0.01, 1000.0))->check(kFinite);
  cmd->add_option("--height", o->height_m, "Height range in metres without a sidecar (as terrain.height)")
      ->check(CLI::Range(0.01, 10000.0))->check(kFinite);
  cmd->callback([o, &exitCode] {
    runCommand("materials", exitCode, [&]() -> Status {
      if (!o->force) {
        for (int l = 0; l < kMaterialLayerCount; ++l) {
          const std::string path = app::materialLayerPath(o->in, MaterialLayer(l));
          std::error_code ec;
          if (std::filesystem::exists(path, ec))
            return makeError(path + " exists; it may hold a designer's work (use --force to overwrite it)");
        }
      }
      TerrainDesc defaults;
      defaults.spacing_m = o->spacing_m;
      defaults.heightScale_m = o->height_m / 65535.0;
      auto t = Terrain::loadPng(o->in, defaults);
      if (!t) return makeError(t.error());
      app::paintMaterials(*t, o->island);
      if (auto st = app::saveMaterialLayersBeside(*t, o->in); !st) return st;
      for (int l = 0; l < kMaterialLayerCount; ++l)
        std::printf("wrote %s\n", app::materialLayerPath(o->in, MaterialLayer(l)).c_str());
      std::fflush(stdout);
      return Ok{};
    });
  });
}

}  // namespace

void addTerrainCommands(CLI::App& terrain, int& exitCode) {
  terrain.require_subcommand(1);
  addGen(terrain, exitCode);
  addSmoothSharpen(terrain, exitCode);
  addConvolve(terrain, exitCode);
  addResample(terrain, exitCode);
  addRidgeCmd(terrain, exitCode);
  addBump(terrain, exitCode);
  addImport(terrain, exitCode);
  addPreview(terrain, exitCode);
  addInfo(terrain, exitCode);
  addMaterials(terrain, exitCode);
}

}  // namespace tumble::tools
