// The verilated rc_board's run, built as a module (model_module.hpp): board_sim.cpp's
// render_board() writes the board image into a directory and calls this module's entry point,
// which loads the ROMs through plusargs, programs the camera and frame registers through the
// register port and reads them back, starts the frame, collects the core's framebuffer writes from
// the monitor port, and afterwards reads the status, cycles, counters and the whole framebuffer
// back through the ports. Built twice: the board (Vrc_board) and the lit board (Vrc_board_lit,
// rc_board Lit = 1), named by RC_BOARD_MODEL and RC_BOARD_MODEL_H.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include RC_BOARD_MODEL_H
#include "board_sim.hpp"
#include "error.hpp"
#include "model_module.hpp"
#include "rc_constants.hpp"
#include "verilated_tb.hpp"

namespace rc::harness {
namespace {

BoardSimResult simulate(const BoardImage& b, const std::filesystem::path& dir,
                        const BoardSimOptions& options) {
  const auto start_time = std::chrono::steady_clock::now();
  std::vector<std::string> args = {"raycore-board"};
  for (const BoardRom& rom : b.roms)
    args.push_back("+" + rom.name + "=" + (dir / (rom.name + ".hex")).string());
  for (const BoardRom& rom : b.light_roms)
    args.push_back("+" + rom.name + "=" + (dir / (rom.name + ".hex")).string());
  args.push_back("+regs=" + (dir / "regs.hex").string());
  // Not fatal on error: an assertion ends the run with a BoardSimError, not abort().
  VerilatedTb<RC_BOARD_MODEL> tb("board", false, args);

  BoardSimResult res;
  const auto fail = [&](const std::string& what) {
    throw BoardSimError("board: " + what + " (cycle " + std::to_string(tb.cycles()) + ")");
  };
  const auto tick = [&] {
    try {
      tb.tick();
    } catch (const TbError&) {
      fail("the RTL stopped (an assertion or $stop; see the message above)");
    }
  };
  tb->reg_we_i = 0;
  tb->start_i = 0;
  tb->fb_raddr_i = 0;
  tb.reset(4, tick);
  tick();

  const auto write_reg = [&](uint32_t addr, uint32_t value) {
    tb->reg_we_i = 1;
    tb->reg_addr_i = static_cast<uint8_t>(addr);
    tb->reg_wdata_i = value;
    tick();
    tb->reg_we_i = 0;
  };
  // A read: the address for one cycle, then the read data spec::kBoardReadLatency cycles on
  // (the address lines change meanwhile, as a pipelined host's would).
  const auto read_reg = [&](uint32_t addr) {
    tb->reg_addr_i = static_cast<uint8_t>(addr);
    tick();
    tb->reg_addr_i = static_cast<uint8_t>(addr ^ 1u);
    for (int64_t k = 1; k < spec::kBoardReadLatency; ++k) tick();
    return static_cast<uint32_t>(tb->reg_rdata_o);
  };

  // Program the camera and the frame size, then read the whole register file back.
  for (uint32_t k = spec::kBoardRegEye; k <= spec::kBoardRegHeight; ++k) write_reg(k, b.regs[k]);
  for (uint32_t k = 0; k < b.regs.size(); ++k)
    if (read_reg(k) != b.regs[k]) ++res.register_readback_differ;

  // The frame.
  Frame& f = res.frame;
  f.width = b.width;
  f.height = b.height;
  const size_t npix = static_cast<size_t>(b.width) * b.height;
  f.rgb.assign(npix * 3, 0);
  f.hit_tri.assign(npix, -1);
  f.hit_t.assign(npix, 0.0f);
  f.hits.assign(npix, HitRecord{});
  res.lit = b.lit;
  if (b.lit) {
    f.light_mask.assign(npix, 0);
    f.bounce_tri.assign(npix, -2);
    f.refract_tri.assign(npix, -2);
  }
  std::vector<uint8_t> seen(npix, 0);
  write_reg(spec::kBoardRegControl, 1u);
  const uint64_t frame_start = tb.cycles();
  while (!tb->done_o) {
    if (tb->size_error_o) fail("the board refused the frame size");
    if (tb->config_error_o) fail("the board refused the light count or depth");
    if (tb->mon_valid_o) {
      const uint32_t pix = tb->mon_pixel_o;
      if (pix >= npix) fail("write to pixel " + std::to_string(pix) + " outside the frame");
      if (seen[pix]++) fail("pixel " + std::to_string(pix) + " written twice");
      const uint32_t rgb = tb->mon_rgb_o;
      for (int c = 0; c < 3; ++c)
        f.rgb[pix * 3 + static_cast<size_t>(c)] = (rgb >> (8 * c)) & 0xffu;
      if (tb->mon_hit_o) {
        f.hits[pix] =
            HitRecord{static_cast<int32_t>(tb->mon_tri_o), tb->mon_t_o, tb->mon_u_o, tb->mon_v_o};
        f.hit_tri[pix] = static_cast<int32_t>(tb->mon_tri_o);
        f.hit_t[pix] = fp24::from_bits(tb->mon_t_o).to_float();
      }
      if (b.lit) {
        f.light_mask[pix] = static_cast<uint32_t>(tb->mon_lights_o);
        f.bounce_tri[pix] = static_cast<int32_t>(tb->mon_bounce_tri_o);
        f.refract_tri[pix] = static_cast<int32_t>(tb->mon_refract_tri_o);
      }
    }
    tick();
    if (tb.cycles() - frame_start > options.watchdog_cycles)
      fail("no done after " + std::to_string(options.watchdog_cycles) + " cycles (status " +
           std::to_string(read_reg(spec::kBoardRegStatus)) + ")");
    if (options.progress && (tb.cycles() & 0xfffff) == 0)
      std::fprintf(stderr, "\rboard: %llu cycles", static_cast<unsigned long long>(tb.cycles()));
  }
  if (options.progress && tb.cycles() - frame_start > 0xfffff) std::fprintf(stderr, "\n");
  for (size_t p = 0; p < npix; ++p)
    if (!seen[p]) fail("pixel " + std::to_string(p) + " never written");

  // Status, cycles, counters and the framebuffer, all through the ports.
  res.status = read_reg(spec::kBoardRegStatus);
  res.error_bits =
      (res.status >> spec::kBoardStatusCoreErrorLsb) & ((1u << spec::kCoreStatusBits) - 1u);
  res.cycles = read_reg(spec::kBoardRegCycles);
  // The counters are exact core.perf_settle_cycles edges after the core's last event; a counter
  // reaches perf_lo/perf_hi core.perf_read_latency + 1 edges after it is named (rc_board's
  // contract), and the register write that names it takes effect at its own edge.
  for (int64_t i = 0; i < spec::kCorePerfSettleCycles; ++i) tick();
  for (int k = 0; k < kCorePerfCount; ++k) {
    write_reg(spec::kBoardRegPerfSel, static_cast<uint32_t>(k));
    for (int64_t i = 0; i < spec::kCorePerfReadLatency + 1; ++i) tick();
    const uint64_t lo = read_reg(spec::kBoardRegPerfLo);
    const uint64_t hi = read_reg(spec::kBoardRegPerfHi);
    res.perf[static_cast<size_t>(k)] = lo | hi << 32;
  }
  f.counters = counters_from_perf(res.perf, res.error_bits);
  for (size_t p = 0; p < npix; ++p) {
    tb->fb_raddr_i = static_cast<std::remove_reference_t<decltype(tb->fb_raddr_i)>>(p);
    for (int64_t k = 0; k < spec::kBoardFbReadLatency; ++k) tick();
    const uint32_t rgb = tb->fb_rdata_o;
    for (int c = 0; c < 3; ++c)
      if (((rgb >> (8 * c)) & 0xffu) != f.rgb[p * 3 + static_cast<size_t>(c)]) {
        ++res.fb_readback_differ;
        break;
      }
  }
  res.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  f.seconds = res.seconds;
  res.cycles_per_second = res.seconds > 0 ? static_cast<double>(tb.cycles()) / res.seconds : 0.0;
  return res;
}

}  // namespace
}  // namespace rc::harness

// Runs the board image written into dir: the result in *out, or a status and the message.
extern "C" __attribute__((visibility("default"))) int rc_board_module_simulate(
    const rc::harness::BoardImage* image, const char* dir,
    const rc::harness::BoardSimOptions* options, rc::harness::BoardSimResult* out,
    std::string* error) {
  using namespace rc::harness;
  return run_in_module<BoardSimError>(error, [&] { *out = simulate(*image, dir, *options); });
}
