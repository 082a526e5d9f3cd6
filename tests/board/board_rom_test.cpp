// The board's ROM (rtl/board/rc_board_rom.sv) alone, in its test bench wrapper, verilated at Width
// 40, Depth 100, IdxW 12, TagW 6 and loaded from a hex file this test writes (+rom=<file>). A model
// of the memory-port protocol drives it with random request gaps and random response stalls (fixed
// seeds) and checks:
//  - every response, in request order: its tag, the record's data, the error bit for an index out
//    of range (indices up to 4095 are asked for; the ROM has 100 records);
//  - a response held back holds, unchanged, until taken;
//  - req_ready_o comes from a register: within a cycle it does not move when rsp_ready_i,
//    req_valid_i, the index or the tag change;
//  - the FIFO entries do not follow the consumer: within a cycle, their write enables
//    (`entry_we`, read through the debug port of the test bench wrapper rc_board_rom_tb.sv) do
//    not move when rsp_ready_i changes (the address and read stages have no enables at all);
//  - four requests are accepted while the consumer stalls (the ROM's credits: they end in the
//    FIFO's three entries and the output register), and no more;
//  - one response per cycle when the consumer never stalls, and no request is lost or hangs.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <deque>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "Vrc_board_rom_tb.h"
#include "verilated_tb.hpp"

namespace {

constexpr uint32_t kDepth = 100;
constexpr uint64_t kDataMask = (uint64_t{1} << 40) - 1;
constexpr uint32_t kTagMask = (1u << 6) - 1;
constexpr uint32_t kIdxMask = (1u << 12) - 1;

struct Expect {
  uint32_t tag;
  bool error;
  uint64_t data;
};

// The ROM's records (seeded random, 40 bits each) and the hex file of them for +rom=.
std::vector<uint64_t> make_rom(std::mt19937& rng) {
  std::vector<uint64_t> rom;
  for (uint32_t i = 0; i < kDepth; ++i) rom.push_back(rng() & kDataMask);
  return rom;
}
std::string write_hex(uint32_t seed, const std::vector<uint64_t>& rom) {
  const std::string file = ::testing::TempDir() + "board_rom_test_" + std::to_string(seed) + ".hex";
  std::ofstream out(file);
  char line[32];
  for (uint64_t v : rom) {
    std::snprintf(line, sizeof line, "%010llx\n", static_cast<unsigned long long>(v));
    out << line;
  }
  return file;
}

class Bench {
 public:
  // Not fatal on error: a failing RTL assertion fails the test (the wrapper's TbError).
  explicit Bench(uint32_t seed)
      : rng_(seed),
        rom_(make_rom(rng_)),
        file_(write_hex(seed, rom_)),
        tb_("rom", /*fatal_on_error=*/false, {"board_rom_test", "+rom=" + file_}) {
    tb_->req_valid_i = 0;
    tb_->rsp_ready_i = 0;
    tb_.reset(2);
  }
  ~Bench() { std::remove(file_.c_str()); }

  // Runs `cycles` cycles: a new request starts with probability p_req when none is waiting
  // (index below 4096, a fifth of them out of range), the consumer is ready with probability
  // p_ready. Returns the number of responses taken.
  uint64_t run(uint64_t cycles, double p_req, double p_ready) {
    std::bernoulli_distribution want_req(p_req), ready(p_ready), far(0.2);
    uint64_t taken = 0;
    for (uint64_t c = 0; c < cycles && !::testing::Test::HasFailure(); ++c) {
      if (!req_valid_ && want_req(rng_)) {
        req_valid_ = true;
        req_index_ = static_cast<uint32_t>(far(rng_) ? (rng_() & kIdxMask) : (rng_() % kDepth));
        req_tag_ = static_cast<uint32_t>(rng_() & kTagMask);
      }
      const bool rsp_ready = ready(rng_);
      taken += cycle(rsp_ready);
    }
    return taken;
  }

  // Takes every response still outstanding, with the consumer always ready; fails if they do
  // not all come within a few cycles.
  void drain() {
    for (int c = 0; c < 16 && (req_valid_ || !expect_.empty()); ++c) cycle(true);
    EXPECT_FALSE(req_valid_) << "a request was never accepted";
    EXPECT_TRUE(expect_.empty()) << expect_.size() << " responses never came";
  }

  uint64_t cycles() const { return tb_.cycles(); }

  // Offers a request on every cycle for `cycles` cycles while the consumer stalls; returns how
  // many were accepted.
  uint64_t fill(uint64_t cycles) {
    uint64_t accepted = 0;
    for (uint64_t c = 0; c < cycles; ++c) {
      if (!req_valid_) {
        req_valid_ = true;
        req_index_ = static_cast<uint32_t>(rng_() % kDepth);
        req_tag_ = static_cast<uint32_t>(rng_() & kTagMask);
      }
      const size_t before = expect_.size();
      cycle(false);
      accepted += expect_.size() - before;
    }
    return accepted;
  }

 private:
  // One clock cycle. Drives the inputs, checks the outputs before the edge, then clocks.
  uint64_t cycle(bool rsp_ready) {
    drive(req_valid_, req_index_, req_tag_, rsp_ready);
    const bool req_ready = tb_->req_ready_o;
    // req_ready_o must not follow anything driven in this cycle.
    drive(!req_valid_, ~req_index_ & kIdxMask, ~req_tag_ & kTagMask, !rsp_ready);
    EXPECT_EQ(bool(tb_->req_ready_o), req_ready)
        << "req_ready_o changed with this cycle's inputs at cycle " << tb_.cycles();
    drive(req_valid_, req_index_, req_tag_, rsp_ready);
    const uint32_t entry_we = tb_->dbg_entry_we_o;
    drive(req_valid_, req_index_, req_tag_, !rsp_ready);
    EXPECT_EQ(uint32_t(tb_->dbg_entry_we_o), entry_we)
        << "the FIFO entries' write enables changed with rsp_ready_i at cycle " << tb_.cycles();
    drive(req_valid_, req_index_, req_tag_, rsp_ready);

    const bool rsp_valid = tb_->rsp_valid_o;
    if (held_) {
      EXPECT_TRUE(rsp_valid) << "a response held back disappeared at cycle " << tb_.cycles();
      EXPECT_EQ(uint32_t(tb_->rsp_tag_o), held_tag_) << "at cycle " << tb_.cycles();
      EXPECT_EQ(uint64_t(tb_->rsp_data_o), held_data_) << "at cycle " << tb_.cycles();
      EXPECT_EQ(bool(tb_->rsp_error_o), held_error_) << "at cycle " << tb_.cycles();
    }
    uint64_t taken = 0;
    if (rsp_valid && rsp_ready) {
      if (expect_.empty()) {
        ADD_FAILURE() << "a response without a request at cycle " << tb_.cycles();
      } else {
        const Expect e = expect_.front();
        expect_.pop_front();
        EXPECT_EQ(uint32_t(tb_->rsp_tag_o), e.tag) << "at cycle " << tb_.cycles();
        EXPECT_EQ(bool(tb_->rsp_error_o), e.error) << "at cycle " << tb_.cycles();
        if (!e.error) {
          EXPECT_EQ(uint64_t(tb_->rsp_data_o), e.data) << "at cycle " << tb_.cycles();
        }
      }
      taken = 1;
    }
    held_ = rsp_valid && !rsp_ready;
    held_tag_ = tb_->rsp_tag_o;
    held_data_ = tb_->rsp_data_o;
    held_error_ = tb_->rsp_error_o;
    if (req_valid_ && req_ready) {
      const bool error = req_index_ >= kDepth;
      expect_.push_back({req_tag_, error, error ? 0 : rom_[req_index_]});
      req_valid_ = false;
    }
    tb_.tick();
    return taken;
  }

  void drive(bool req_valid, uint32_t index, uint32_t tag, bool rsp_ready) {
    tb_->req_valid_i = req_valid;
    tb_->req_index_i = static_cast<SData>(index);
    tb_->req_tag_i = static_cast<CData>(tag);
    tb_->rsp_ready_i = rsp_ready;
    tb_.eval();
  }

  std::mt19937 rng_;
  std::vector<uint64_t> rom_;
  std::string file_;
  rc::harness::VerilatedTb<Vrc_board_rom_tb> tb_;
  bool req_valid_ = false;
  uint32_t req_index_ = 0, req_tag_ = 0;
  std::deque<Expect> expect_;
  bool held_ = false, held_error_ = false;
  uint32_t held_tag_ = 0;
  uint64_t held_data_ = 0;
};

TEST(BoardRom, RandomGapsAndStalls) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    for (double p_req : {0.3, 0.9, 1.0}) {
      for (double p_ready : {0.1, 0.5, 0.9}) {
        SCOPED_TRACE("seed " + std::to_string(seed) + ", p_req " + std::to_string(p_req) +
                     ", p_ready " + std::to_string(p_ready));
        Bench b(seed);
        const uint64_t taken = b.run(20000, p_req, p_ready);
        EXPECT_GT(taken, 1000u);
        b.drain();
      }
    }
  }
}

// A stalled consumer: the ROM takes four requests (its credits), which end in the FIFO's three
// entries and the output register; then req_ready_o stays 0, and all four come out in order.
TEST(BoardRom, FourHeldWhileStalled) {
  Bench b(11);
  EXPECT_EQ(b.fill(50), 4u);
  b.drain();
}

// With requests on every cycle and a consumer that never stalls, the ROM answers once per
// cycle after its three cycles of latency (plus the cycle in which the first request is made).
TEST(BoardRom, FullThroughput) {
  Bench b(7);
  const uint64_t taken = b.run(10000, 1.0, 1.0);
  EXPECT_GE(taken, 10000u - 4u);
  b.drain();
}

}  // namespace
