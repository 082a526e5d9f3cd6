// The board build (rtl/board/rc_board.sv, docs/fpga.md) from the C++ side:
// - BoardImage: a memory image as the board's block RAM contents (one hex file per ROM, one line
//   per index, exactly the response rc::harness::MemoryPort gives for it: a record, for the node
//   ROM the pair {record i + 1 (zero for the last), record i}) and its register file (camera
//   registers from rc::camera_registers(), frame size, background, root box, record counts,
//   shading constants, the root node's record). `raycore board-image` writes it for the FPGA
//   flow. A frame lit by the scene's lights (--lighting scene, a scene with lights) needs the lit
//   board (rc_board Lit = 1: rc_tracer around the core): two more ROMs for its lighting ports
//   (the shading records, the materials' lighting fields) and the light registers.
// - render_board(): the verilated rc_board (model Vrc_board, Vrc_board_lit when lit) renders a
//   frame: the harness loads
//   the ROMs through plusargs, programs the camera and frame registers through the register port
//   and reads them back, starts the frame, collects the core's framebuffer writes from the
//   monitor port, and afterwards reads the whole framebuffer back through its read port.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "core_sim.hpp"
#include "image.hpp"
#include "render.hpp"

namespace rc::harness {

struct BoardRom {
  std::string name;    // nodes, lists, tris, shading, materials (the plusarg and file stem)
  uint32_t width = 0;  // line bits (the port's response data width)
  std::vector<std::vector<uint32_t>> records;  // little-endian words per line (index)
  uint32_t depth() const { return records.empty() ? 1u : static_cast<uint32_t>(records.size()); }
};

struct BoardImage {
  std::array<BoardRom, kCorePorts> roms;  // in CorePort order
  // The lit board's: lshading, lmaterials (rc_tracer's lighting ports); empty when not lit.
  std::vector<BoardRom> light_roms;
  bool lit = false;
  // The register file (spec::kBoardRegs entries; spec::kBoardLitRegs when lit).
  std::vector<uint32_t> regs;
  uint32_t width = 0, height = 0;
  uint32_t fb_pixels = 0;  // the framebuffer the image was made for (rc_board FbPixels)
};

// Whether a frame of `render` over `image` is lit by the scene's lights (--lighting scene and a
// scene with lights): the lit board renders it.
bool board_lit(const scene::SceneImage& image, const RenderOptions& render);

// The board's contents for a frame of `render` (size, camera, background; lit: the lights, the
// depth) over an fp24 image. Throws scene::Error when the image is not fp24, the frame does not
// fit (fb_pixels), or a lit frame has more lights than the tracer holds or a depth above its limit.
BoardImage make_board_image(const scene::SceneImage& image, const RenderOptions& render,
                            uint32_t fb_pixels);

// Writes <dir>/{nodes,lists,tris,shading,materials,regs}.hex ($readmemh), when lit
// <dir>/{lshading,lmaterials}.hex, and <dir>/board.json (depths, frame size, the parameters the
// FPGA flow passes to rc_board, Lit among them). Creates dir.
void write_board_image(const BoardImage& b, const std::string& dir, const std::string& source);
// The names of the files write_board_image() writes into its directory.
std::vector<std::string> board_image_files();

struct BoardSimOptions {
  uint64_t watchdog_cycles = 2000000;  // fail when the frame takes longer than this
  bool progress = false;
};

struct BoardSimResult {
  // From the monitor: rgb, exact hit records (lit: the lights and first mirror and refraction
  // hits too); counters from the perf registers (lit: the core's, over every kind).
  Frame frame;
  bool lit = false;
  uint64_t cycles = 0;      // the board's cycle register for the frame
  uint32_t status = 0;      // the status register after the frame
  uint32_t error_bits = 0;  // rc_core error_o (status bits from core_error_lsb)
  std::array<uint64_t, kCorePerfCount> perf{};
  uint64_t fb_readback_differ = 0;  // framebuffer pixels whose read-back rgb differs
  uint64_t register_readback_differ = 0;
  double seconds = 0.0, cycles_per_second = 0.0;
};

class BoardSimError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The largest frame the verilated board models hold (their FbPixels parameter).
uint32_t board_model_fb_pixels();

// Renders through the verilated board. Throws scene::Error for an unusable image or frame and
// BoardSimError for a failed run (hang, pixel written twice or never, assertion).
BoardSimResult render_board(const scene::SceneImage& image, const RenderOptions& render,
                            const BoardSimOptions& options);

}  // namespace rc::harness
