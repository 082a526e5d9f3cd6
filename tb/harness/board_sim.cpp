// The board build's C++ side (board_sim.hpp): block RAM contents, and the verilated rc_board's
// run (board_module.cpp, a module: model_module.hpp).
#include "board_sim.hpp"

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "error.hpp"
#include "geometry.hpp"
#include "model_module.hpp"
#include "rc_constants.hpp"

namespace rc::harness {

namespace {

constexpr unsigned kW = fp24::kWidth;

// ROM line bits per port: rc_core's response data widths (the node port's is a pair of records).
constexpr std::array<uint32_t, kCorePorts> kRecordBits = {
    static_cast<uint32_t>(spec::kCoreNodeRspRecords * spec::kKdNodeBytes * 8), 32, 12 * kW,
    32 + 4 * kW, 96};
constexpr std::array<const char*, kCorePorts> kRomNames = {"nodes", "lists", "tris", "shading",
                                                           "materials"};
// The lit board's two more ROMs (rc_tracer's lighting ports) and their line bits.
constexpr std::array<const char*, 2> kLightRomNames = {"lshading", "lmaterials"};
constexpr std::array<uint32_t, 2> kLightRecordBits = {
    32 + 4 * kW, static_cast<uint32_t>(8 * (spec::kImageMaterialEta + 4 - spec::kImageMaterialKd))};

// A ROM's lines: the port's response for each index (for the nodes: records k and k + 1).
BoardRom rom_of(const MemoryPort& p, const char* name, uint32_t width) {
  BoardRom rom;
  rom.name = name;
  rom.width = width;
  if (p.data_words() * 32 < rom.width || p.response_bytes() * 8 > rom.width)
    throw std::logic_error("board ROM " + rom.name + ": response of " +
                           std::to_string(p.response_bytes()) + " bytes, port of " +
                           std::to_string(rom.width) + " bits");
  rom.records.reserve(p.count());
  for (uint64_t k = 0; k < p.count(); ++k) rom.records.push_back(p.record_words(k));
  return rom;
}

std::string hex_record(const std::vector<uint32_t>& words, uint32_t bits) {
  static const char* digits = "0123456789abcdef";
  const uint32_t n = (bits + 3) / 4;
  std::string s(n, '0');
  for (uint32_t d = 0; d < n; ++d) {  // digit d holds bits 4d .. 4d+3
    const uint32_t w = (4 * d) / 32, sh = (4 * d) % 32;
    const uint32_t v = w < words.size() ? (words[w] >> sh) & 0xfu : 0u;
    s[n - 1 - d] = digits[v];
  }
  return s;
}

void write_text(const std::filesystem::path& p, const std::string& text) {
  std::ofstream out(p);
  out << text;
  if (!out) throw scene::Error("cannot write " + p.string());
}

std::string regs_hex(const std::vector<uint32_t>& regs) {
  std::ostringstream ss;
  for (uint32_t v : regs) ss << hex_record({v}, 32) << "\n";
  return ss.str();
}

}  // namespace

// As render_rtl() decides it (core_sim.cpp): the image's lights section, without loading the
// geometry.
bool board_lit(const scene::SceneImage& image, const RenderOptions& render) {
  return render.lighting == Lighting::kScene && image.light_count() > 0;
}

BoardImage make_board_image(const scene::SceneImage& image, const RenderOptions& render,
                            uint32_t fb_pixels) {
  if (!image.format().is<fp24>())
    throw scene::Error(image.name() + ": the board is built for fp24 (7/16), the image holds " +
                       image.format().name());
  const uint64_t pixels = static_cast<uint64_t>(render.width) * render.height;
  if (pixels > fb_pixels)
    throw scene::Error("the frame " + std::to_string(render.width) + "x" +
                       std::to_string(render.height) + " (" + std::to_string(pixels) +
                       " pixels) does not fit the board's framebuffer of " +
                       std::to_string(fb_pixels) + " pixels");
  if (render.width >= (1u << spec::kBoardCoordBits) ||
      render.height >= (1u << spec::kBoardCoordBits))
    throw scene::Error("the frame is wider or higher than the board's coordinate registers");
  BoardImage b;
  b.width = render.width;
  b.height = render.height;
  b.fb_pixels = fb_pixels;
  b.lit = board_lit(image, render);
  const auto ports = make_core_ports(image, std::array<MemoryParams, kCorePorts>{});
  for (size_t i = 0; i < static_cast<size_t>(kCorePorts); ++i)
    b.roms[i] = rom_of(*ports[i], kRomNames[i], kRecordBits[i]);
  b.regs.assign(b.lit ? spec::kBoardLitRegs : spec::kBoardRegs, 0u);
  if (b.lit) {
    // The tracer's configuration, as render_rtl() gives it (load_geometry(), lit_params()).
    const Geometry<fp24> g = load_geometry<fp24>(image);
    if (g.lights.size() > static_cast<size_t>(spec::kLightMaxLights))
      throw scene::Error(image.name() + ": the lit board holds " +
                         std::to_string(spec::kLightMaxLights) + " lights, the scene has " +
                         std::to_string(g.lights.size()));
    if (render.max_bounces > static_cast<uint32_t>(spec::kLightBounceLimit))
      throw scene::Error("the lit board traces to depth " +
                         std::to_string(spec::kLightBounceLimit) + " at most, not " +
                         std::to_string(render.max_bounces));
    const auto lports = make_light_ports(image, MemoryParams{}, MemoryParams{});
    for (size_t i = 0; i < 2; ++i)
      b.light_roms.push_back(rom_of(*lports[i], kLightRomNames[i], kLightRecordBits[i]));
    b.regs[spec::kBoardRegLightCount] = static_cast<uint32_t>(g.lights.size());
    b.regs[spec::kBoardRegMaxBounces] = render.max_bounces;
    b.regs[spec::kBoardRegTEps] = g.t_eps.bits();
    const LitParams<fp24> lp = lit_params<fp24>(render.max_bounces, render.background);
    for (unsigned c = 0; c < 3; ++c) b.regs[spec::kBoardRegLightBg + c] = lp.background[c].bits();
    for (size_t l = 0; l < g.lights.size(); ++l) {
      if (g.lights[l].directional) b.regs[spec::kBoardRegLightDir] |= 1u << l;
      for (unsigned a = 0; a < 3; ++a) {
        b.regs[spec::kBoardRegLights + 6 * l + a] = g.lights[l].pos[a].bits();
        b.regs[spec::kBoardRegLights + 6 * l + 3 + a] = g.lights[l].color[a].bits();
      }
    }
  }
  const auto cam = round_registers<fp24>(camera_registers(render.camera, b.width, b.height));
  for (unsigned a = 0; a < 3; ++a) {
    b.regs[spec::kBoardRegEye + a] = cam.eye[a].bits();
    b.regs[spec::kBoardRegC0 + a] = cam.c0[a].bits();
    b.regs[spec::kBoardRegCx + a] = cam.cx[a].bits();
    b.regs[spec::kBoardRegCy + a] = cam.cy[a].bits();
  }
  b.regs[spec::kBoardRegWidth] = b.width;
  b.regs[spec::kBoardRegHeight] = b.height;
  b.regs[spec::kBoardRegBackground] = static_cast<uint32_t>(render.background[0]) |
                                      static_cast<uint32_t>(render.background[1]) << 8 |
                                      static_cast<uint32_t>(render.background[2]) << 16;
  const auto bounds = image.bounds_bits();
  for (unsigned i = 0; i < 6; ++i) b.regs[spec::kBoardRegBounds + i] = bounds[i];
  b.regs[spec::kBoardRegNodeCount] =
      image.section(static_cast<uint32_t>(spec::kImageSectionIdNodes)).count;
  b.regs[spec::kBoardRegListCount] =
      image.section(static_cast<uint32_t>(spec::kImageSectionIdLists)).count;
  b.regs[spec::kBoardRegTriCount] =
      image.section(static_cast<uint32_t>(spec::kImageSectionIdTriangles)).count;
  b.regs[spec::kBoardRegAmbient] = shade_ambient<fp24>().bits();
  b.regs[spec::kBoardRegDiffuse] = shade_diffuse<fp24>().bits();
  const uint64_t root = root_node_record(image);
  b.regs[spec::kBoardRegRoot] = static_cast<uint32_t>(root);
  b.regs[spec::kBoardRegRoot + 1] = static_cast<uint32_t>(root >> 32);
  return b;
}

std::vector<std::string> board_image_files() {
  std::vector<std::string> names;
  for (const char* rom : kRomNames) names.push_back(std::string(rom) + ".hex");
  for (const char* rom : kLightRomNames) names.push_back(std::string(rom) + ".hex");
  names.push_back("regs.hex");
  names.push_back("board.json");
  return names;
}

void write_board_image(const BoardImage& b, const std::string& dir, const std::string& source) {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  nlohmann::json depths, params;
  std::vector<const BoardRom*> roms;
  std::vector<const char*> depth_params = {"NodeDepth", "ListDepth", "TriDepth", "ShdDepth",
                                           "MatDepth"};
  std::vector<const char*> hex_params = {"NodeHex", "ListHex", "TriHex", "ShdHex", "MatHex"};
  for (const BoardRom& rom : b.roms) roms.push_back(&rom);
  for (const BoardRom& rom : b.light_roms) roms.push_back(&rom);
  if (b.lit) {
    depth_params.insert(depth_params.end(), {"LShdDepth", "LMatDepth"});
    hex_params.insert(hex_params.end(), {"LShdHex", "LMatHex"});
  }
  for (size_t i = 0; i < roms.size(); ++i) {
    const BoardRom& rom = *roms[i];
    std::ostringstream ss;
    for (const auto& r : rom.records) ss << hex_record(r, rom.width) << "\n";
    if (rom.records.empty()) ss << hex_record({}, rom.width) << "\n";  // a ROM needs a record
    const fs::path file = fs::path(dir) / (rom.name + ".hex");
    write_text(file, ss.str());
    depths[rom.name] = {{"records", rom.records.size()},
                        {"depth", rom.depth()},
                        {"bits", rom.width},
                        {"file", rom.name + ".hex"}};
    params[depth_params[i]] = rom.depth();
    params[hex_params[i]] = rom.name + ".hex";
  }
  write_text(fs::path(dir) / "regs.hex", regs_hex(b.regs));
  params["RegsHex"] = "regs.hex";
  params["FbPixels"] = b.fb_pixels;
  params["Lit"] = b.lit ? 1 : 0;
  const nlohmann::json j = {{"source", source},
                            {"width", b.width},
                            {"height", b.height},
                            {"roms", depths},
                            {"rc_board_params", params}};
  write_text(fs::path(dir) / "board.json", j.dump(2) + "\n");
}

uint32_t board_model_fb_pixels() { return RC_BOARD_SIM_FbPixels; }

namespace {
// The lit board model's lighting ROM depths (tb/harness/CMakeLists.txt).
constexpr uint32_t kLightModelDepth[2] = {RC_BOARD_SIM_LShdDepth, RC_BOARD_SIM_LMatDepth};
}  // namespace

BoardSimResult render_board(const scene::SceneImage& image, const RenderOptions& render,
                            const BoardSimOptions& options) {
  namespace fs = std::filesystem;
  using ModuleSimulate =
      int(const BoardImage*, const char*, const BoardSimOptions*, BoardSimResult*, std::string*);
  const BoardImage b = make_board_image(image, render, board_model_fb_pixels());
  auto* simulate = reinterpret_cast<ModuleSimulate*>(
      module_symbol(b.lit ? "rc_board_lit_model" : "rc_board_model", "rc_board_module_simulate"));
  const uint32_t model_depth[kCorePorts] = {RC_BOARD_SIM_NodeDepth, RC_BOARD_SIM_ListDepth,
                                            RC_BOARD_SIM_TriDepth, RC_BOARD_SIM_ShdDepth,
                                            RC_BOARD_SIM_MatDepth};
  for (int i = 0; i < kCorePorts; ++i)
    if (b.roms[static_cast<size_t>(i)].records.size() > model_depth[i])
      throw scene::Error(
          image.name() + ": " + std::to_string(b.roms[static_cast<size_t>(i)].records.size()) +
          " " + kRomNames[static_cast<size_t>(i)] +
          " records do not fit the verilated board's ROM of " + std::to_string(model_depth[i]));
  for (size_t i = 0; i < b.light_roms.size(); ++i)
    if (b.light_roms[i].records.size() > kLightModelDepth[i])
      throw scene::Error(image.name() + ": " + std::to_string(b.light_roms[i].records.size()) +
                         " " + b.light_roms[i].name +
                         " records do not fit the verilated board's ROM of " +
                         std::to_string(kLightModelDepth[i]));

  // The ROM contents as the FPGA flow writes them; the register file starts with the scene's
  // configuration but no camera and no frame size: those go through the register port.
  static std::atomic<unsigned> run_counter{0};
  const fs::path dir = fs::temp_directory_path() / ("raycore-board-" + std::to_string(::getpid()) +
                                                    "-" + std::to_string(run_counter.fetch_add(1)));
  write_board_image(b, dir.string(), image.name());
  std::vector<uint32_t> initial = b.regs;
  for (uint32_t k = spec::kBoardRegEye; k <= spec::kBoardRegHeight; ++k) initial[k] = 0;
  write_text(dir / "regs.hex", regs_hex(initial));
  struct Cleanup {
    fs::path dir;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
  } cleanup{dir};

  BoardSimResult res;
  std::string error;
  rethrow_module_status<BoardSimError>(simulate(&b, dir.c_str(), &options, &res, &error), error);
  return res;  // seconds and cycles per second: the simulation's own
}

}  // namespace rc::harness
