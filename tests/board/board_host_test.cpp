// The board build's host link (rtl/board/rc_uart_tx.sv, rc_uart_rx.sv, rc_board_host.sv) in the
// test bench rc_board_host_tb.sv, 8 clocks per bit:
//  - rc_uart_tx -> rc_uart_rx loopback of random bytes (with random gaps and back to back);
//  - rc_board_host driven bit by bit on its serial line by this test's own 8N1 encoder, its
//    answers decoded by this test's own decoder (which also checks every bit lasts exactly
//    8 clocks), against a model of the fake register file and framebuffer: W, R, S and F bit for
//    bit, unknown bytes, bytes dropped during an answer, the command timeout, frames larger than
//    the framebuffer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "Vrc_board_host_tb.h"
#include "rc_constants.hpp"
#include "verilated_tb.hpp"

namespace {

constexpr int kClksPerBit = 8;      // ClkHz / Baud of the test bench
constexpr uint32_t kFbPixels = 64;  // FbPixels of the test bench
constexpr uint64_t kTimeout = 400;  // TimeoutCycles of the test bench
constexpr int kRegs = 256;

constexpr uint8_t kW = 'W', kR = 'R', kS = 'S', kF = 'F';

uint32_t reg_init(uint32_t a) { return (a * 0x01010101u) ^ 0xA5C30F96u; }

struct Write {
  uint32_t addr, data;
};

class Bench {
 public:
  // Not fatal on error: a failing RTL assertion fails the test (the wrapper's TbError).
  Bench() : tb_("tb", /*fatal_on_error=*/false) {
    for (uint32_t a = 0; a < kRegs; ++a) regs_.push_back(reg_init(a));
    fb_.assign(kFbPixels, 0);
    tb_->lb_valid_i = 0;
    tb_->lb_data_i = 0;
    tb_->rx_i = 1;
    tb_->fb_we_i = 0;
    tb_.reset(3, [this] { tick(); });
    tick();
  }

  Vrc_board_host_tb& m() { return tb_.m(); }
  uint64_t cycle() const { return tb_.cycles(); }

  // One clock cycle: the serial encoder drives rx_i, then a rising edge; then the decoder and the
  // monitors look at the outputs after the edge.
  void tick() {
    drive_rx();
    tb_.tick();
    decode_tx();
    if (tb_->mon_we_o) {
      writes_.push_back({tb_->mon_addr_o, tb_->mon_wdata_o});
      regs_[tb_->mon_addr_o] = tb_->mon_wdata_o;
    }
    drops_ += tb_->drop_o;
    rx_frame_errors_ += tb_->rx_frame_error_o;
  }

  // Queue bytes on the host's serial line (8N1, 8 clocks per bit); gap = idle bit times before.
  // With set_jitter(j), every bit boundary after the start edge moves by a random -j .. j clocks
  // (a receiver sampling in the middle of the bit still sees every bit; one sampling near an edge
  // does not).
  void send(const std::vector<uint8_t>& bytes, int gap_bits = 0) {
    for (uint8_t b : bytes) {
      for (int i = 0; i < gap_bits * kClksPerBit; ++i) line_.push_back(1);
      gap_bits = 0;
      std::vector<int> bits = {0};
      for (int k = 0; k < 8; ++k) bits.push_back((b >> k) & 1);
      bits.push_back(1);
      int prev_end = 0;
      for (size_t k = 0; k < bits.size(); ++k) {
        int end = static_cast<int>(k + 1) * kClksPerBit;
        if (jitter_ > 0 && k + 1 < bits.size())
          end += static_cast<int>(jitter_rng_() % static_cast<unsigned>(2 * jitter_ + 1)) - jitter_;
        for (int i = prev_end; i < end; ++i) line_.push_back(bits[k]);
        prev_end = end;
      }
    }
  }
  void set_jitter(int clocks) { jitter_ = clocks; }
  // Queue a glitch: the line low for a few clocks (shorter than half a bit).
  void glitch(int clocks) {
    for (int i = 0; i < clocks; ++i) line_.push_back(0);
    for (int i = 0; i < 2 * kClksPerBit; ++i) line_.push_back(1);
  }
  bool sending() const { return !line_.empty(); }

  // Run until the line is sent and the host's answer (if any) has been quiet for 3 frames (at
  // most 2000 byte times: a garbled command may ask for a huge frame).
  void settle() {
    while (sending()) tick();
    uint64_t quiet = 0;
    const uint64_t limit = cycle() + 2000 * 10 * kClksPerBit;
    while (quiet < 30 * kClksPerBit) {
      if (cycle() > limit) {
        ADD_FAILURE() << "the host still answers after 2000 byte times";
        return;
      }
      const size_t before = answer_.size();
      const bool in_frame = decoding_;
      tick();
      quiet = (answer_.size() != before || in_frame) ? 0 : quiet + 1;
    }
  }
  void run(uint64_t cycles) {
    for (uint64_t i = 0; i < cycles; ++i) tick();
  }

  std::vector<uint8_t> take_answer() { return std::exchange(answer_, {}); }
  std::vector<Write> take_writes() { return std::exchange(writes_, {}); }
  uint64_t drops() const { return drops_; }
  uint64_t rx_frame_errors() const { return rx_frame_errors_; }
  uint64_t tx_timing_errors() const { return tx_timing_errors_; }
  const std::vector<uint32_t>& regs() const { return regs_; }
  const std::vector<uint32_t>& fb() const { return fb_; }

  void fill_fb(std::mt19937& rng) {
    for (uint32_t p = 0; p < kFbPixels; ++p) {
      fb_[p] = static_cast<uint32_t>(rng() & 0xffffffu);
      tb_->fb_we_i = 1;
      tb_->fb_waddr_i = static_cast<uint8_t>(p);
      tb_->fb_wdata_i = fb_[p];
      tick();
    }
    tb_->fb_we_i = 0;
  }

 private:
  void drive_rx() {
    if (line_.empty()) {
      tb_->rx_i = 1;
    } else {
      tb_->rx_i = static_cast<uint8_t>(line_.front());
      line_.pop_front();
    }
  }

  // 8N1 decoder of tx_o: a falling edge starts a frame; every bit must hold for exactly
  // kClksPerBit clocks (the start bit counted from the edge); the stop bit must be 1.
  void decode_tx() {
    const int level = tb_->tx_o;
    if (!decoding_) {
      if (level == 0) {
        decoding_ = true;
        frame_clk_ = 0;
        byte_ = 0;
      }
    }
    if (decoding_) {
      const int bit = frame_clk_ / kClksPerBit;  // 0 start, 1..8 data, 9 stop
      const int expect_level = bit == 0 ? 0 : bit == 9 ? 1 : -1;
      if (frame_clk_ % kClksPerBit == 0) {
        if (bit >= 1 && bit <= 8) {
          byte_ |= static_cast<uint8_t>(level << (bit - 1));
          bit_level_ = level;
        }
      } else if (bit >= 1 && bit <= 8 && level != bit_level_) {
        ++tx_timing_errors_;
      }
      if (expect_level >= 0 && level != expect_level) ++tx_timing_errors_;
      ++frame_clk_;
      // The stop bit's last clock: the next clock may be the next start bit.
      if (frame_clk_ == 10 * kClksPerBit) {
        answer_.push_back(byte_);
        decoding_ = false;
      }
    }
  }

  rc::harness::VerilatedTb<Vrc_board_host_tb> tb_;
  std::deque<int> line_;
  int jitter_ = 0;
  std::mt19937 jitter_rng_{7};
  bool decoding_ = false;
  int frame_clk_ = 0, bit_level_ = 1;
  uint8_t byte_ = 0;
  std::vector<uint8_t> answer_;
  std::vector<Write> writes_;
  std::vector<uint32_t> regs_, fb_;
  uint64_t drops_ = 0, rx_frame_errors_ = 0, tx_timing_errors_ = 0;
};

std::vector<uint8_t> le32(uint32_t v) {
  return {static_cast<uint8_t>(v), static_cast<uint8_t>(v >> 8), static_cast<uint8_t>(v >> 16),
          static_cast<uint8_t>(v >> 24)};
}

std::vector<uint8_t> write_cmd(uint32_t addr, uint32_t v) {
  std::vector<uint8_t> c = {kW, static_cast<uint8_t>(addr)};
  for (uint8_t b : le32(v)) c.push_back(b);
  return c;
}

// The bytes an 'F' answers for a width x height frame (width/height: the registers' low 16 bits).
std::vector<uint8_t> expected_frame(const Bench& b) {
  const uint32_t w = b.regs()[rc::spec::kBoardRegWidth] & 0xffffu;
  const uint32_t h = b.regs()[rc::spec::kBoardRegHeight] & 0xffffu;
  std::vector<uint8_t> out;
  for (uint32_t p = 0; p < w * h; ++p) {
    const uint32_t rgb = p < kFbPixels ? b.fb()[p] : 0;
    for (int c = 0; c < 3; ++c) out.push_back(static_cast<uint8_t>(rgb >> (8 * c)));
  }
  return out;
}

bool is_command(uint8_t c) { return c == kW || c == kR || c == kS || c == kF; }

TEST(UartLoopback, RandomBytes) {
  Bench b;
  std::mt19937 rng(1);
  std::vector<uint8_t> sent, got;
  uint64_t frame_errors = 0, last_take = 0, min_spacing = ~0ull;
  const int n = 3000;
  int gap = 0;
  while (got.size() < static_cast<size_t>(n)) {
    if (!b.m().lb_valid_i && sent.size() < static_cast<size_t>(n) && gap == 0) {
      b.m().lb_valid_i = 1;
      b.m().lb_data_i = static_cast<uint8_t>(rng());
    }
    b.m().eval();
    const bool take = b.m().lb_valid_i && b.m().lb_ready_o;
    const uint8_t data = b.m().lb_data_i;
    b.tick();
    if (take) {
      if (!sent.empty()) min_spacing = std::min(min_spacing, b.cycle() - last_take);
      last_take = b.cycle();
      sent.push_back(data);
      b.m().lb_valid_i = 0;
      // Half of the bytes back to back, the rest after a random gap of up to 3 bit times.
      gap = (rng() & 1) ? static_cast<int>(rng() % (3 * kClksPerBit)) : 0;
    } else if (gap > 0) {
      --gap;
    }
    if (b.m().lb_rx_valid_o) got.push_back(b.m().lb_rx_data_o);
    frame_errors += b.m().lb_rx_frame_error_o;
    ASSERT_LT(b.cycle(), 200ull * kClksPerBit * 10 * n) << "loopback stalled";
  }
  int mismatches = 0;
  for (int i = 0; i < n; ++i)
    mismatches += sent[static_cast<size_t>(i)] != got[static_cast<size_t>(i)];
  std::printf("[cases] uart loopback: %d cases, %d mismatches\n", n, mismatches);
  EXPECT_EQ(mismatches, 0);
  EXPECT_EQ(frame_errors, 0u);
  EXPECT_EQ(min_spacing, static_cast<uint64_t>(10 * kClksPerBit)) << "back to back: one frame "
                                                                     "per 10 bit times";
  EXPECT_EQ(b.m().lb_line_o, 1) << "the line idles high";
}

TEST(BoardHost, WriteReadStart) {
  Bench b;
  std::mt19937 rng(2);
  int cases = 0, mismatches = 0;
  for (int i = 0; i < 300; ++i) {
    const uint32_t addr = static_cast<uint32_t>(rng() & 0xffu);
    const auto value = static_cast<uint32_t>(rng());
    const int kind = static_cast<int>(rng() % 4);
    if (kind == 0) {
      b.send({kS}, static_cast<int>(rng() % 3));
      b.settle();
      const auto w = b.take_writes();
      const bool ok = w.size() == 1 && w[0].addr == rc::spec::kBoardRegControl && w[0].data == 1 &&
                      b.take_answer().empty();
      mismatches += !ok;
      EXPECT_TRUE(ok) << "S: one write of 1 to BoardRegControl";
    } else if (kind == 1) {
      b.send(write_cmd(addr, value), static_cast<int>(rng() % 3));
      b.settle();
      const auto w = b.take_writes();
      const bool ok =
          w.size() == 1 && w[0].addr == addr && w[0].data == value && b.take_answer().empty();
      mismatches += !ok;
      EXPECT_TRUE(ok) << "W " << addr << " " << value;
    } else {
      const uint32_t expect = b.regs()[addr];
      b.send({kR, static_cast<uint8_t>(addr)}, static_cast<int>(rng() % 3));
      b.settle();
      const auto a = b.take_answer();
      const bool ok = a == le32(expect) && b.take_writes().empty();
      mismatches += !ok;
      EXPECT_TRUE(ok) << "R " << addr;
    }
    ++cases;
  }
  // Unknown bytes between commands: no write, no answer.
  std::vector<uint8_t> junk;
  while (junk.size() < 200) {
    const auto c = static_cast<uint8_t>(rng());
    if (!is_command(c)) junk.push_back(c);
  }
  b.send(junk);
  b.settle();
  ++cases;
  const bool junk_ok = b.take_writes().empty() && b.take_answer().empty();
  mismatches += !junk_ok;
  EXPECT_TRUE(junk_ok) << "unknown bytes are ignored";
  // A glitch shorter than half a bit is not a start bit.
  b.glitch(kClksPerBit / 2 - 2);
  b.send({kR, 7});
  b.settle();
  ++cases;
  const bool glitch_ok = b.take_answer() == le32(b.regs()[7]);
  mismatches += !glitch_ok;
  EXPECT_TRUE(glitch_ok) << "a glitch is ignored";
  EXPECT_EQ(b.drops(), 0u);
  EXPECT_EQ(b.rx_frame_errors(), 0u);
  EXPECT_EQ(b.tx_timing_errors(), 0u);
  cases += 3;
  mismatches += (b.drops() != 0) + (b.rx_frame_errors() != 0) + (b.tx_timing_errors() != 0);
  std::printf("[cases] board host W/R/S: %d cases, %d mismatches\n", cases, mismatches);
}

TEST(BoardHost, JitteredBits) {
  // Bit edges moved by up to 3 of the 8 clocks: the receiver samples in the middle of each bit.
  Bench b;
  b.set_jitter(3);
  std::mt19937 rng(4);
  int mismatches = 0;
  const int n = 200;
  for (int i = 0; i < n; ++i) {
    const auto addr = static_cast<uint32_t>(rng() & 0xffu);
    const auto value = static_cast<uint32_t>(rng());
    b.send(write_cmd(addr, value));
    b.send({kR, static_cast<uint8_t>(addr)});
    b.settle();
    const auto w = b.take_writes();
    const bool ok =
        w.size() == 1 && w[0].addr == addr && w[0].data == value && b.take_answer() == le32(value);
    mismatches += !ok;
    EXPECT_TRUE(ok) << "W/R " << addr << " " << value << " with jittered bit edges";
  }
  std::printf("[cases] board host jittered bits: %d cases, %d mismatches\n", n, mismatches);
  EXPECT_EQ(b.rx_frame_errors(), 0u);
}

TEST(BoardHost, Frame) {
  Bench b;
  std::mt19937 rng(3);
  b.fill_fb(rng);
  // (width, height) pairs: the framebuffer exactly, smaller ones, a row, a column, empty ones, and
  // larger than the framebuffer (pixels beyond it are sent as 0); upper register bits ignored.
  const std::vector<std::pair<uint32_t, uint32_t>> sizes = {
      {8, 8}, {5, 7}, {1, 1}, {13, 1}, {1, 9}, {0, 5}, {5, 0}, {9, 8}, {0x30006, 0x10003}};
  int cases = 0, mismatches = 0;
  for (const auto& [w, h] : sizes) {
    b.send(write_cmd(rc::spec::kBoardRegWidth, w));
    b.send(write_cmd(rc::spec::kBoardRegHeight, h), 1);
    b.send({kF}, 2);
    b.settle();
    const auto a = b.take_answer();
    const auto e = expected_frame(b);
    ++cases;
    const bool ok = a == e && b.take_writes().size() == 2;
    mismatches += !ok;
    EXPECT_TRUE(ok) << "F at " << w << "x" << h << ": " << a.size() << " bytes, expected "
                    << e.size();
  }
  EXPECT_EQ(b.drops(), 0u);
  EXPECT_EQ(b.tx_timing_errors(), 0u);
  cases += 2;
  mismatches += (b.drops() != 0) + (b.tx_timing_errors() != 0);
  std::printf("[cases] board host F: %d cases, %d mismatches\n", cases, mismatches);
}

TEST(BoardHost, DropAndTimeout) {
  Bench b;
  int cases = 0, mismatches = 0;
  const auto check = [&](bool ok, const char* what) {
    ++cases;
    mismatches += !ok;
    EXPECT_TRUE(ok) << what;
  };
  // A command byte arriving during an answer is dropped: 'S' right behind an 'R'.
  b.send({kR, 3, kS});
  b.settle();
  check(b.take_answer() == le32(b.regs()[3]), "the R answers");
  check(b.take_writes().empty(), "the 'S' sent during the answer is dropped");
  check(b.drops() == 1u, "one drop counted");

  // An unfinished 'W' is abandoned after TimeoutCycles: nothing is written and the next bytes are
  // a new command.
  b.send({kW, 5, 0x11, 0x22});
  while (b.sending()) b.tick();
  b.run(kTimeout + 2 * kClksPerBit);
  b.send({kR, 5});
  b.settle();
  check(b.take_writes().empty(), "the abandoned W wrote nothing");
  check(b.take_answer() == le32(reg_init(5)), "the R after the timeout reads the old value");
  // Just inside the timeout the command goes on.
  b.send({kW, 6, 0x11, 0x22});
  while (b.sending()) b.tick();
  b.run(kTimeout - 12 * kClksPerBit);
  b.send({0x33, 0x44});
  b.settle();
  const auto w = b.take_writes();
  check(w.size() == 1u && w[0].addr == 6u && w[0].data == 0x44332211u,
        "the W finished inside the timeout writes 0x44332211 to register 6");
  check(b.tx_timing_errors() == 0u, "no transmit timing error");
  std::printf("[cases] board host drop and timeout: %d cases, %d mismatches\n", cases, mismatches);
}

}  // namespace
